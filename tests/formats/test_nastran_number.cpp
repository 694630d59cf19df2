#include <catch2/catch.hpp>

#include "formats/nastran_number.hpp"

using namespace ssid::formats;

TEST_CASE("NASTRAN real forms parse exactly", "[number]") {
  CHECK(*parse_real("1.") == 1.0);
  CHECK(*parse_real(".5") == 0.5);
  CHECK(*parse_real("1.-3") == 1e-3);
  CHECK(*parse_real("-2.5+4") == -2.5e4);
  CHECK(*parse_real("1.E-3") == 1e-3);
  CHECK(*parse_real("1.D-3") == 1e-3);
  CHECK(*parse_real("1.e+3") == 1e3);
  CHECK(*parse_real("+3.25") == 3.25);
  CHECK(*parse_real("7") == 7.0);  // integer where a real is allowed
  CHECK(*parse_real("0.1") == 0.1);
  CHECK(!parse_real("1.5.2"));
  CHECK(!parse_real("E5"));
  CHECK(!parse_real("."));
  CHECK(!parse_real("1.E"));
  CHECK(!parse_real("1.5X"));
  CHECK(!parse_real(""));
  CHECK(!parse_real("1.+999"));  // overflow is an error, not infinity
}

TEST_CASE("NASTRAN integers", "[number]") {
  CHECK(*parse_integer("12") == 12);
  CHECK(*parse_integer("-3") == -3);
  CHECK(*parse_integer("+4") == 4);
  CHECK(!parse_integer("1.5"));
  CHECK(!parse_integer("1.0"));
  CHECK(!parse_integer("99999999999999999999"));
  CHECK(classify_field("") == FieldKind::Blank);
  CHECK(classify_field("12") == FieldKind::Integer);
  CHECK(classify_field("1.-3") == FieldKind::Real);
  CHECK(classify_field("TUBE") == FieldKind::Text);
}

TEST_CASE("real formatting is shortest, exact and always has a decimal point", "[number]") {
  CHECK(*format_real_exact(1.0, 8) == "1.");
  CHECK(*format_real_exact(0.5, 8) == ".5");
  CHECK(*format_real_exact(-0.001, 8) == "-.001");
  CHECK(*format_real_exact(1.5e-5, 8) == "1.5-5");
  CHECK(*format_real_exact(1e20, 8) == "1.+20");
  CHECK(*format_real_exact(100.0, 8) == "100.");
  CHECK(*format_real_exact(0.0, 8) == "0.");
  CHECK(*format_real_exact(12.5, 8) == "12.5");
  CHECK(!format_real_exact(0.1234567891, 8));
  CHECK(*format_real_exact(0.1234567891, 16) == ".1234567891");
  CHECK(format_real_rounded(0.1234567891, 8) == ".1234568");
  CHECK(format_real_rounded(-1.2345678901234567e-300, 16).size() <= 16);
  // Every formatted value reads back to the same double.
  std::uint64_t state = 12345;
  for (int k = 0; k < 20000; ++k) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    double mant = static_cast<double>(state >> 11) / static_cast<double>(1ULL << 53) - 0.5;
    int e = static_cast<int>((state >> 3) % 60) - 30;
    double v = mant * std::pow(10.0, e);
    auto s = format_real_exact(v, 32);
    REQUIRE(s);
    REQUIRE(s->find('.') != std::string::npos);
    REQUIRE(*parse_real(*s) == v);
  }
}
