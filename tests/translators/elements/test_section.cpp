#include <catch2/catch.hpp>

#include <cmath>

#include "formats/cards/section.hpp"
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
  // Symmetric I: depth 10, flanges 6 x 1, web 0.5: I1 = (B H³ − (B − tw) hw³)/12;
  // J: flanges 6 t³/3 each, the web from flange mid-line to mid-line (9) t_w³/3.
  check_props(section_properties(SectionShape::I, {10.0, 6.0, 6.0, 0.5, 1.0, 1.0}), 16.0,
              (6 * 1000.0 - 5.5 * 512.0) / 12, (2 * 216.0 + 8 * 0.125) / 12, (12.0 + 9 * 0.125) / 3);
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
                                   {SectionShape::I, {12.0, 8.0, 4.0, 0.6, 1.2, 0.8}},
                                   {SectionShape::Tube2, {1.3, 0.2}},
                                   {SectionShape::I1, {3.0, 0.4, 5.0, 6.5}},
                                   {SectionShape::Chan, {3.0, 6.0, 0.4, 0.5}},
                                   {SectionShape::Chan1, {2.5, 0.4, 5.0, 6.0}},
                                   {SectionShape::Chan2, {0.3, 0.4, 2.0, 5.0}},
                                   {SectionShape::T, {4.0, 5.0, 0.5, 0.3}},
                                   {SectionShape::T1, {4.0, 5.0, 0.5, 0.3}},
                                   {SectionShape::T2, {4.0, 5.0, 0.5, 0.3}},
                                   {SectionShape::L, {3.0, 4.0, 0.3, 0.4}},
                                   {SectionShape::Box1, {5.0, 3.0, 0.3, 0.2, 0.4, 0.5}},
                                   {SectionShape::Cross, {3.0, 0.5, 4.0, 0.4}},
                                   {SectionShape::H, {3.0, 0.8, 4.0, 0.4}},
                                   {SectionShape::Z, {2.5, 0.4, 5.0, 6.0}},
                                   {SectionShape::Hexa, {0.5, 3.0, 1.7}},
                                   {SectionShape::Hat, {3.0, 0.2, 2.5, 0.8}},
                                   {SectionShape::Hat1, {4.0, 2.0, 2.0, 0.15, 0.2}},
                                   {SectionShape::DBox, {6.0, 2.0, 3.5, 0.2, 0.3, 0.25, 0.15, 0.2, 0.1, 0.3}}};
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
  CHECK_THROWS_WITH(parse_section_shape("HAT9"), Contains("HAT9") && Contains("HAT1, DBOX)"));
  CHECK_THROWS_WITH(section_properties(SectionShape::Chan2, {1.0, 0.1, 2.0, 1.5}),
                    "PBARL/PBEAML TYPE=CHAN2: 2*DIM1 (legs) must be smaller than the width DIM4");
  CHECK_THROWS_WITH(section_properties(SectionShape::Hexa, {1.0, 2.0, 1.0}),
                    "PBARL/PBEAML TYPE=HEXA: 2*DIM1 (the tips) must be smaller than the width DIM2");
  CHECK_THROWS_WITH(section_properties(SectionShape::DBox, {4, 2, 2, .1, .1, .1, .1, .1, 1.2, 1.0}),
                    "PBARL/PBEAML TYPE=DBOX: DIM7 + DIM8 and DIM9 + DIM10 must be smaller than DIM2");
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

TEST_CASE("PBARL sections: TYPE=T as NX Nastran printed its equivalent PBAR", "[section]") {
  // fict_mass.f06 (NX Nastran 2007, USER INFORMATION MESSAGE 4379) for
  // PBARL 3200 T 0.03 0.03 0.004 0.004 and PBARL 3300 T 0.01 0.01 0.002 0.002,
  // five printed digits each: A, I1, I2, J, K1, K2. The J printed is the
  // thin-walled sum with the web running to the flange's mid-line.
  const auto a = section_properties(SectionShape::T, {0.03, 0.03, 0.004, 0.004});
  CHECK(a.a == Approx(2.2400e-4).epsilon(5e-5));
  CHECK(a.i1 == Approx(1.8554e-8).epsilon(5e-5));
  CHECK(a.i2 == Approx(9.1387e-9).epsilon(5e-5));
  CHECK(a.j == Approx(1.2373e-9).epsilon(5e-5));
  CHECK(a.k1 == Approx(4.6429e-1).epsilon(5e-5));
  CHECK(a.k2 == Approx(5.3571e-1).epsilon(5e-5));
  const auto b = section_properties(SectionShape::T, {0.01, 0.01, 0.002, 0.002});
  CHECK(b.a == Approx(3.6000e-5).epsilon(5e-5));
  CHECK(b.i1 == Approx(3.1422e-10).epsilon(5e-5));
  CHECK(b.i2 == Approx(1.7200e-10).epsilon(5e-5));
  CHECK(b.j == Approx(5.0667e-11).epsilon(5e-5));
  CHECK(b.k1 == Approx(4.4444e-1).epsilon(5e-5));
  CHECK(b.k2 == Approx(5.5556e-1).epsilon(5e-5));
}

TEST_CASE("PBARL sections: area equals MSC's published area formula for every type", "[section]") {
  // The beam library's area expressions in the DIMi (MSC), an independent
  // statement of what each dimension means.
  struct Case {
    const char* type;
    std::vector<double> d;
    double area;
  };
  const double pi = M_PI;
  auto D = [](const std::vector<double>& d, int i) { return d[static_cast<std::size_t>(i - 1)]; };
  std::vector<Case> cases = {
      {"ROD", {0.7}, 0}, {"TUBE", {1.3, 0.9}, 0}, {"TUBE2", {1.3, 0.2}, 0}, {"I", {12, 8, 4, 0.6, 1.2, 0.8}, 0},
      {"I1", {3, 0.4, 5, 6.5}, 0}, {"CHAN", {3, 6, 0.4, 0.5}, 0}, {"CHAN1", {2.5, 0.4, 5, 6}, 0},
      {"CHAN2", {0.3, 0.4, 2, 5}, 0}, {"T", {4, 5, 0.5, 0.3}, 0}, {"T1", {4, 5, 0.5, 0.3}, 0},
      {"T2", {4, 5, 0.5, 0.3}, 0}, {"BOX", {5, 3, 0.3, 0.4}, 0}, {"BOX1", {5, 3, 0.3, 0.2, 0.4, 0.5}, 0},
      {"BAR", {2, 3}, 0}, {"CROSS", {3, 0.5, 4, 0.4}, 0}, {"H", {3, 0.8, 4, 0.4}, 0}, {"Z", {2.5, 0.4, 5, 6}, 0},
      {"HEXA", {0.5, 3, 1.7}, 0}, {"HAT", {3, 0.2, 2.5, 0.8}, 0}, {"HAT1", {4, 2, 2, 0.15, 0.2}, 0},
      {"DBOX", {6, 2, 3.5, 0.2, 0.3, 0.25, 0.15, 0.2, 0.1, 0.3}, 0}, {"L", {3, 4, 0.3, 0.4}, 0}};
  for (auto& c : cases) {
    const auto& d = c.d;
    const std::string t = c.type;
    if (t == "ROD") c.area = pi * D(d, 1) * D(d, 1);
    if (t == "TUBE") c.area = pi * (D(d, 1) * D(d, 1) - D(d, 2) * D(d, 2));
    if (t == "TUBE2") c.area = pi * (D(d, 1) * D(d, 1) - (D(d, 1) - D(d, 2)) * (D(d, 1) - D(d, 2)));
    if (t == "I") c.area = D(d, 3) * D(d, 6) + D(d, 2) * D(d, 5) + (D(d, 1) - (D(d, 5) + D(d, 6))) * D(d, 4);
    if (t == "I1" || t == "CHAN1" || t == "Z") c.area = D(d, 2) * D(d, 3) + (D(d, 4) - D(d, 3)) * (D(d, 1) + D(d, 2));
    if (t == "CHAN") c.area = 2 * D(d, 1) * D(d, 4) + (D(d, 2) - 2 * D(d, 4)) * D(d, 3);
    if (t == "CHAN2") c.area = 2 * D(d, 1) * D(d, 3) + (D(d, 4) - 2 * D(d, 1)) * D(d, 2);
    if (t == "T" || t == "T2") c.area = D(d, 1) * D(d, 3) + (D(d, 2) - D(d, 3)) * D(d, 4);
    if (t == "T1") c.area = D(d, 1) * D(d, 3) + D(d, 2) * D(d, 4);
    if (t == "BOX") c.area = 2 * D(d, 1) * D(d, 3) + 2 * (D(d, 2) - 2 * D(d, 3)) * D(d, 4);
    if (t == "BOX1")
      c.area = D(d, 2) * D(d, 6) + D(d, 2) * D(d, 5) + (D(d, 1) - D(d, 5) - D(d, 6)) * (D(d, 3) + D(d, 4));
    if (t == "BAR") c.area = D(d, 1) * D(d, 2);
    if (t == "CROSS") c.area = D(d, 2) * D(d, 3) + 2 * (0.5 * D(d, 1)) * D(d, 4);
    if (t == "H") c.area = 2 * (0.5 * D(d, 2)) * D(d, 3) + D(d, 1) * D(d, 4);
    if (t == "HEXA") c.area = (D(d, 2) - 2 * D(d, 1)) * D(d, 3) + D(d, 3) * D(d, 1);
    if (t == "HAT") c.area = D(d, 2) * D(d, 3) + 2 * (D(d, 1) - D(d, 2)) * D(d, 2) + 2 * D(d, 2) * D(d, 4);
    if (t == "HAT1")
      c.area = D(d, 1) * D(d, 5) + D(d, 3) * D(d, 4) + (D(d, 1) - D(d, 3)) * D(d, 4) +
               2 * (D(d, 2) - D(d, 5) - D(d, 4)) * D(d, 4);
    if (t == "DBOX")
      c.area = (D(d, 2) * D(d, 3) - (D(d, 2) - D(d, 7) - D(d, 8)) * (D(d, 3) - (0.5 * D(d, 5) + D(d, 4)))) +
               ((D(d, 1) - D(d, 3)) * D(d, 2) -
                (D(d, 2) - (D(d, 9) + D(d, 10))) * (D(d, 1) - D(d, 3) - 0.5 * D(d, 5) - D(d, 6)));
    if (t == "L") c.area = D(d, 1) * D(d, 3) + (D(d, 2) - D(d, 3)) * D(d, 4);
    INFO(t);
    REQUIRE(c.area > 0);
    const SectionShape s = parse_section_shape(t);
    CHECK(section_properties(s, d).a == Approx(c.area).epsilon(1e-13));
    // The card reader and the section library know the same types and counts.
    CHECK(ssid::formats::pbarl_dim_count(t) == section_dim_count(s));
    CHECK(ssid::formats::pbarl_type_sectioned(t));
  }
  CHECK(cases.size() == 22);  // every type of the QRG list (with TUBE2, HAT1, DBOX, L)
}

TEST_CASE("PBARL sections: the new types against hand values and each other", "[section]") {
  auto same = [](const SectionProperties& p, const SectionProperties& q) {
    CHECK(p.a == Approx(q.a).epsilon(1e-13));
    CHECK(p.i1 == Approx(q.i1).epsilon(1e-13));
    CHECK(p.i2 == Approx(q.i2).epsilon(1e-13));
    CHECK(p.i12 == Approx(q.i12).margin(1e-13));
    CHECK(p.j == Approx(q.j).epsilon(1e-13));
    CHECK(p.k1 == Approx(q.k1).epsilon(1e-13));
    CHECK(p.k2 == Approx(q.k2).epsilon(1e-13));
  };
  // Equivalent descriptions of one shape.
  same(section_properties(SectionShape::Tube2, {1.3, 0.2}), section_properties(SectionShape::Tube, {1.3, 1.1}));
  same(section_properties(SectionShape::T2, {4, 5, 0.5, 0.3}), section_properties(SectionShape::T, {4, 5, 0.5, 0.3}));
  // I1 (outstands 3 + web 0.4, web 5 clear, depth 6.5) = I with flanges 3.4 x 0.75.
  same(section_properties(SectionShape::I1, {3, 0.4, 5, 6.5}),
       section_properties(SectionShape::I, {6.5, 3.4, 3.4, 0.4, 0.75, 0.75}));
  // CHAN1 (outstand 2.5, web 0.4, clear 5, depth 6) = CHAN 2.9 wide, flanges 0.5.
  same(section_properties(SectionShape::Chan1, {2.5, 0.4, 5, 6}), section_properties(SectionShape::Chan, {2.9, 6, 0.4, 0.5}));
  // BOX1 with equal opposite walls = BOX.
  same(section_properties(SectionShape::Box1, {5, 3, 0.3, 0.3, 0.4, 0.4}),
       section_properties(SectionShape::Box, {5, 3, 0.3, 0.4}));
  // DBOX of two equal cells, all walls t: the middle wall carries no shear flow,
  // so J is the single cell's (BOX); A, I add the middle wall.
  {
    const double t = 0.1, b = 4, h = 2;
    const auto d = section_properties(SectionShape::DBox, {b, h, b / 2, t, t, t, t, t, t, t});
    const auto box = section_properties(SectionShape::Box, {b, h, t, t});
    CHECK(d.j == Approx(box.j).epsilon(1e-13));
    CHECK(d.a == Approx(box.a + t * (h - 2 * t)).epsilon(1e-13));
    CHECK(d.i1 == Approx(box.i1 + t * std::pow(h - 2 * t, 3) / 12).epsilon(1e-13));
    CHECK(d.i2 == Approx(box.i2 + (h - 2 * t) * t * t * t / 12).epsilon(1e-13));
    CHECK(d.i12 == Approx(0.0).margin(1e-13));
  }
  // Regular hexagon of side s (tips s/2, width 2s, height s√3):
  // A = 3√3 s²/2, I1 = I2 = 5√3 s⁴/16.
  {
    const double s = 1.3, r3 = std::sqrt(3.0);
    const auto p = section_properties(SectionShape::Hexa, {s / 2, 2 * s, s * r3});
    CHECK(p.a == Approx(1.5 * r3 * s * s).epsilon(1e-13));
    CHECK(p.i1 == Approx(5 * r3 * std::pow(s, 4) / 16).epsilon(1e-13));
    CHECK(p.i2 == Approx(5 * r3 * std::pow(s, 4) / 16).epsilon(1e-13));
    CHECK(p.i12 == 0.0);
  }
  // Equal-leg angle 1 x 1, t = 0.1, by hand: corner 0.1², legs 0.9 x 0.1;
  // ȳ = z̄ = 0.0545/0.19, I12 = Σ A (y − ȳ)(z − z̄) < 0 (legs along +y and +z).
  {
    const auto p = section_properties(SectionShape::L, {1, 1, 0.1, 0.1});
    const double c = 0.0545 / 0.19;
    const double i12 = 0.01 * (0.05 - c) * (0.05 - c) + 2 * 0.09 * (0.05 - c) * (0.55 - c);
    const double ii = 0.1 * 0.001 / 12 + 0.9 * 0.001 / 12 + 0.1 * 0.729 / 12 + 0.01 * (0.05 - c) * (0.05 - c) +
                      0.09 * (0.05 - c) * (0.05 - c) + 0.09 * (0.55 - c) * (0.55 - c);
    CHECK(p.a == Approx(0.19).epsilon(1e-13));
    CHECK(p.i12 == Approx(i12).epsilon(1e-12));
    CHECK(p.i12 < 0);
    CHECK(p.i1 == Approx(ii).epsilon(1e-12));
    CHECK(p.i2 == Approx(ii).epsilon(1e-12));
    // Centre-line legs 0.95 each; shear areas clear of the corner.
    CHECK(p.j == Approx(2 * 0.95 * 0.001 / 3).epsilon(1e-13));
    CHECK(p.k1 == Approx(0.09 / 0.19).epsilon(1e-13));
  }
  // Z: point-symmetric, so the centroid is the web's centre; I12 from the flanges.
  {
    const double bo = 2.5, tw = 0.4, hw = 5, h = 6, tf = 0.5;
    const auto p = section_properties(SectionShape::Z, {bo, tw, hw, h});
    const double af = (bo + tw) * tf, yf = (hw + tf) / 2, zf = bo / 2;  // flange centroid offsets
    CHECK(p.i12 == Approx(-2 * af * yf * zf).epsilon(1e-12));
    const auto c = section_properties(SectionShape::Chan1, {bo, tw, hw, h});
    CHECK(p.i1 == Approx(c.i1).epsilon(1e-13));
    CHECK(p.j == Approx(c.j).epsilon(1e-13));
    CHECK(p.i2 == Approx(hw * tw * tw * tw / 12 + 2 * ((bo + tw) * std::pow(bo + tw, 2) * tf / 12 + af * zf * zf))
                      .epsilon(1e-12));
  }
  // CROSS and H by rectangles.
  {
    const double arms = 3, tv = 0.5, hv = 4, th = 0.4;
    const auto p = section_properties(SectionShape::Cross, {arms, tv, hv, th});
    CHECK(p.i1 == Approx(tv * hv * hv * hv / 12 + arms * th * th * th / 12).epsilon(1e-13));
    CHECK(p.i2 == Approx(hv * tv * tv * tv / 12 + th * (std::pow(arms + tv, 3) - tv * tv * tv) / 12).epsilon(1e-13));
    CHECK(p.k1 == Approx(tv * hv / p.a).epsilon(1e-13));
    const double gap = 3, tl = 0.4, hl = 4, tw = 0.4;
    const auto q = section_properties(SectionShape::H, {gap, 2 * tl, hl, tw});
    CHECK(q.i1 == Approx(2 * tl * hl * hl * hl / 12 + gap * tw * tw * tw / 12).epsilon(1e-13));
    CHECK(q.i2 == Approx(hl * (std::pow(gap + 2 * tl, 3) - gap * gap * gap) / 12 + tw * gap * gap * gap / 12)
                      .epsilon(1e-13));
  }
  // CHAN2 (U of legs 0.3, base 0.4, height 2, width 5) about its centroid.
  {
    const double tl = 0.3, tb = 0.4, h = 2, b = 5;
    const auto p = section_properties(SectionShape::Chan2, {tl, tb, h, b});
    const double al = tl * h, ab = (b - 2 * tl) * tb, a = 2 * al + ab;
    const double yc = (2 * al * h / 2 + ab * tb / 2) / a;
    CHECK(p.i1 == Approx(2 * (tl * h * h * h / 12 + al * (h / 2 - yc) * (h / 2 - yc)) + (b - 2 * tl) * tb * tb * tb / 12 +
                         ab * (tb / 2 - yc) * (tb / 2 - yc))
                      .epsilon(1e-12));
    CHECK(p.i2 == Approx((h * b * b * b - h * std::pow(b - 2 * tl, 3)) / 12 + tb * std::pow(b - 2 * tl, 3) / 12)
                      .epsilon(1e-12));
    CHECK(p.j == Approx((2 * (h - tb / 2) * tl * tl * tl + (b - tl) * tb * tb * tb) / 3).epsilon(1e-13));
  }
  // Shear centre: symmetric types assemble on CBEAM, the others are refused there.
  CHECK(shear_centre_at_centroid(SectionShape::I, {10, 6, 6, 0.5, 1, 1}));
  CHECK_FALSE(shear_centre_at_centroid(SectionShape::I, {10, 6, 4, 0.5, 1, 1}));
  CHECK_FALSE(shear_centre_at_centroid(SectionShape::Chan, {3, 6, 0.4, 0.5}));
  CHECK(shear_centre_at_centroid(SectionShape::Z, {2.5, 0.4, 5, 6}));
}
