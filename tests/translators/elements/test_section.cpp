#include <catch2/catch.hpp>

#include <cmath>

#include "translators/elements/section.hpp"

using namespace ssid::translators::elements;

namespace {
void check_props(const SectionProperties& p, double a, double i1, double i2, double j, double tol = 1e-12) {
  CHECK(p.a == Approx(a).epsilon(tol));
  CHECK(p.i1 == Approx(i1).epsilon(tol));
  CHECK(p.i2 == Approx(i2).epsilon(tol));
  CHECK(p.i12 == 0.0);
  CHECK(p.j == Approx(j).epsilon(tol));
}
}  // namespace

TEST_CASE("PBARL sections: properties by hand", "[section]") {
  const double pi = M_PI;
  check_props(section_properties(SectionShape::Rod, {2.0}), 4 * pi, 4 * pi, 4 * pi, 8 * pi);
  check_props(section_properties(SectionShape::Tube, {2.0, 1.0}), 3 * pi, 15 * pi / 4, 15 * pi / 4, 15 * pi / 2);
  // BAR 3 (along z) x 1 (along y): I1 = b h³/12 = 0.25, I2 = h b³/12 = 2.25.
  // Roark: a=3, c=1: J = 3 (1/3 − 0.21/3 (1 − 1/972)).
  check_props(section_properties(SectionShape::Bar, {3.0, 1.0}), 3.0, 0.25, 2.25,
              3.0 * (1.0 / 3.0 - 0.07 * (1.0 - 1.0 / 972.0)));
  // The PBARL example BOX 10 x 6, walls 0.5: inner 9 x 5.
  check_props(section_properties(SectionShape::Box, {10.0, 6.0, 0.5, 0.5}), 15.0, (10 * 216.0 - 9 * 125.0) / 12,
              (6 * 1000.0 - 5 * 729.0) / 12, 2 * 0.25 * 90.25 * 30.25 / 7.5);
  // Symmetric I: depth 10, flanges 6 x 1, web 0.5: I1 = (B H³ − (B − tw) hw³)/12.
  check_props(section_properties(SectionShape::I, {10.0, 6.0, 6.0, 0.5, 1.0, 1.0}), 16.0,
              (6 * 1000.0 - 5.5 * 512.0) / 12, (2 * 216.0 + 8 * 0.125) / 12, (12.0 + 8 * 0.125) / 3);
}

TEST_CASE("PBARL sections: unsymmetric I about its centroid, J limits", "[section]") {
  // I with unequal flanges: second moment about the bottom face by plates,
  // then moved to the centroid: I1 = I_bottom − A ȳ².
  const double h = 12, bb = 8, bt = 4, tw = 0.6, tb = 1.2, tt = 0.8;
  const double hw = h - tb - tt;
  auto plate = [](double b, double y0, double y1) { return b * (y1 * y1 * y1 - y0 * y0 * y0) / 3.0; };
  const double A = bb * tb + tw * hw + bt * tt;
  const double Sy = bb * tb * tb / 2 + tw * hw * (tb + hw / 2) + bt * tt * (h - tt / 2);
  const double Ib = plate(bb, 0, tb) + plate(tw, tb, tb + hw) + plate(bt, h - tt, h);
  const SectionProperties p = section_properties(SectionShape::I, {h, bb, bt, tw, tb, tt});
  CHECK(p.a == Approx(A));
  CHECK(p.i1 == Approx(Ib - Sy * Sy / A).epsilon(1e-13));
  // Square BAR: Roark's approximation within 0.5 % of the exact 0.140577 a⁴.
  CHECK(section_properties(SectionShape::Bar, {2.0, 2.0}).j == Approx(0.140577 * 16).epsilon(5e-3));
  // BAR J is symmetric in its two dimensions; thin strip tends to b t³/3.
  CHECK(section_properties(SectionShape::Bar, {1.0, 3.0}).j == Approx(section_properties(SectionShape::Bar, {3.0, 1.0}).j));
  CHECK(section_properties(SectionShape::Bar, {100.0, 0.1}).j == Approx(100 * 1e-3 / 3).epsilon(1e-3));
  // Thin tube: J -> 2 π r³ t (mean radius).
  CHECK(section_properties(SectionShape::Tube, {1.0005, 0.9995}).j == Approx(2 * M_PI * 1e-3).epsilon(1e-6));
}

TEST_CASE("PBARL sections: Jacobian matches central differences for every dimension", "[section]") {
  struct Case {
    SectionShape s;
    std::vector<double> d;
  };
  const std::vector<Case> cases = {{SectionShape::Rod, {0.7}},
                                   {SectionShape::Tube, {1.3, 0.9}},
                                   {SectionShape::Bar, {0.8, 2.1}},
                                   {SectionShape::Bar, {2.1, 0.8}},
                                   {SectionShape::Box, {5.0, 3.0, 0.4, 0.3}},
                                   {SectionShape::I, {12.0, 8.0, 4.0, 0.6, 1.2, 0.8}}};
  for (const auto& c : cases) {
    const auto jac = section_jacobian(c.s, c.d);
    for (std::size_t k = 0; k < c.d.size(); ++k) {
      const double h = 1e-5 * c.d[k];
      auto dp = c.d, dm = c.d;
      dp[k] += h, dm[k] -= h;
      const SectionProperties p = section_properties(c.s, dp), m = section_properties(c.s, dm);
      const double fd[kSectionValues] = {(p.a - m.a) / (2 * h),     (p.i1 - m.i1) / (2 * h),
                                         (p.i2 - m.i2) / (2 * h),   (p.i12 - m.i12) / (2 * h),
                                         (p.j - m.j) / (2 * h),     (p.k1 - m.k1) / (2 * h),
                                         (p.k2 - m.k2) / (2 * h)};
      for (int r = 0; r < kSectionValues; ++r) {
        INFO(section_shape_name(c.s) << " DIM" << k + 1 << " row " << r);
        CHECK(jac(r, k) == Approx(fd[r]).epsilon(1e-7).margin(1e-9 * jac.cwiseAbs().maxCoeff()));
      }
    }
  }
}

TEST_CASE("PBARL sections: bad dimensions are refused with the type named", "[section]") {
  using Catch::Matchers::Contains;
  CHECK_THROWS_WITH(section_properties(SectionShape::Tube, {1.0, 1.0}), Contains("TUBE") && Contains("inner"));
  CHECK_THROWS_WITH(section_properties(SectionShape::Box, {1.0, 2.0, 0.5}), Contains("expected 4"));
  CHECK_THROWS_WITH(section_properties(SectionShape::I, {1.0, 1.0, 1.0, 0.1, 0.5, 0.5}), Contains("DIM5 + DIM6"));
  CHECK_THROWS_WITH(section_properties(SectionShape::Rod, {-1.0}), Contains("DIM1 must be > 0"));
  CHECK_THROWS_WITH(parse_section_shape("HAT"), Contains("HAT"));
  CHECK(parse_section_shape("BOX") == SectionShape::Box);
}

TEST_CASE("PBARL sections: shear factors as NASTRAN prints them for its equivalent PBAR", "[section]") {
  // Values NX Nastran printed (USER INFORMATION MESSAGE 4379) for the same
  // dimensions, to the five digits it prints: ROD r = 1 -> 0.9, 0.9;
  // TUBE 0.2/0.195 -> 0.5, 0.5; BOX 6 x 1, walls 0.1 -> 0.11765, 0.85294
  // (docs/elements.md names the .f06 files).
  const auto rod = section_properties(SectionShape::Rod, {1.0});
  CHECK(rod.k1 == 0.9);
  CHECK(rod.k2 == 0.9);
  const auto tube = section_properties(SectionShape::Tube, {0.2, 0.195});
  CHECK(tube.a == Approx(6.2047e-3).epsilon(1e-4));
  CHECK(tube.k1 == 0.5);
  CHECK(tube.k2 == 0.5);
  const auto box = section_properties(SectionShape::Box, {6.0, 1.0, 0.1, 0.1});
  CHECK(box.a == Approx(1.36).epsilon(1e-12));
  CHECK(box.i1 == Approx(0.25253).epsilon(5e-5));
  CHECK(box.i2 == Approx(4.9925).epsilon(5e-5));
  CHECK(box.j == Approx(0.82930).epsilon(5e-5));
  CHECK(box.k1 == Approx(0.11765).epsilon(5e-5));
  CHECK(box.k2 == Approx(0.85294).epsilon(5e-5));
  // I by the same rule (web, flanges over A): depth 10, flanges 6 x 1, web 0.5.
  const auto i = section_properties(SectionShape::I, {10.0, 6.0, 6.0, 0.5, 1.0, 1.0});
  CHECK(i.k1 == Approx(4.0 / 16.0).epsilon(1e-14));
  CHECK(i.k2 == Approx(12.0 / 16.0).epsilon(1e-14));
  const auto bar = section_properties(SectionShape::Bar, {3.0, 1.0});
  CHECK(bar.k1 == Approx(5.0 / 6.0).epsilon(1e-15));
  CHECK(bar.k2 == Approx(5.0 / 6.0).epsilon(1e-15));
}
