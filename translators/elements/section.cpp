#include "translators/elements/section.hpp"

#include <array>
#include <cmath>
#include <iterator>
#include <stdexcept>

#include "translators/elements/complex_step.hpp"

namespace ssid::translators::elements {

namespace {
using detail::real_part;

struct ShapeInfo {
  const char* name;
  int dims;
};

// In the order of SectionShape.
constexpr ShapeInfo kShapes[] = {
    {"ROD", 1},   {"TUBE", 2}, {"BAR", 2},   {"BOX", 4},   {"I", 6},    {"TUBE2", 2}, {"I1", 4},
    {"CHAN", 4},  {"CHAN1", 4}, {"CHAN2", 4}, {"T", 4},     {"T1", 4},   {"T2", 4},    {"L", 4},
    {"BOX1", 6},  {"CROSS", 4}, {"H", 4},     {"Z", 4},     {"HEXA", 3}, {"HAT", 4},   {"HAT1", 5},
    {"DBOX", 10},
};

std::invalid_argument bad(SectionShape s, const std::string& what) {
  return std::invalid_argument(std::string("PBARL/PBEAML TYPE=") + section_shape_name(s) + ": " + what);
}

/// One geometric condition of a type: `ok` must hold, else the message names what failed.
void need(SectionShape s, bool ok, const char* what) {
  if (!ok) throw bad(s, what);
}

void check_dims(SectionShape s, const std::vector<double>& d) {
  if (static_cast<int>(d.size()) != section_dim_count(s))
    throw bad(s, "expected " + std::to_string(section_dim_count(s)) + " dimensions, got " +
                     std::to_string(d.size()));
  for (std::size_t i = 0; i < d.size(); ++i)
    if (!(d[i] > 0.0)) throw bad(s, "DIM" + std::to_string(i + 1) + " must be > 0, got " + std::to_string(d[i]));
  switch (s) {
    case SectionShape::Tube:
      need(s, d[1] < d[0], "inner radius DIM2 must be smaller than outer radius DIM1");
      break;
    case SectionShape::Tube2:
      need(s, d[1] < d[0], "wall thickness DIM2 must be smaller than the outer radius DIM1");
      break;
    case SectionShape::Box:
      need(s, 2 * d[2] < d[1], "2*DIM3 (top/bottom walls) must be smaller than the height DIM2");
      need(s, 2 * d[3] < d[0], "2*DIM4 (side walls) must be smaller than the width DIM1");
      break;
    case SectionShape::I:
      need(s, d[4] + d[5] < d[0], "flange thicknesses DIM5 + DIM6 must be smaller than the depth DIM1");
      need(s, d[3] < d[1] && d[3] < d[2], "web thickness DIM4 must be smaller than the flange widths DIM2, DIM3");
      break;
    case SectionShape::I1:
    case SectionShape::Chan1:
    case SectionShape::Z:
      need(s, d[2] < d[3], "web height DIM3 must be smaller than the depth DIM4");
      break;
    case SectionShape::Chan:
      need(s, 2 * d[3] < d[1], "2*DIM4 (flanges) must be smaller than the depth DIM2");
      need(s, d[2] < d[0], "web thickness DIM3 must be smaller than the flange width DIM1");
      break;
    case SectionShape::Chan2:
      need(s, d[1] < d[2], "base thickness DIM2 must be smaller than the height DIM3");
      need(s, 2 * d[0] < d[3], "2*DIM1 (legs) must be smaller than the width DIM4");
      break;
    case SectionShape::T:
    case SectionShape::T2:
      need(s, d[2] < d[1], "flange thickness DIM3 must be smaller than the height DIM2");
      need(s, d[3] < d[0], "web thickness DIM4 must be smaller than the flange width DIM1");
      break;
    case SectionShape::T1:
      need(s, d[3] < d[0], "web thickness DIM4 must be smaller than the flange height DIM1");
      break;
    case SectionShape::L:
      need(s, d[2] < d[1], "DIM3 must be smaller than the height DIM2");
      need(s, d[3] < d[0], "DIM4 must be smaller than the width DIM1");
      break;
    case SectionShape::Box1:
      need(s, d[2] + d[3] < d[1], "DIM3 + DIM4 (top and bottom walls) must be smaller than the height DIM2");
      need(s, d[4] + d[5] < d[0], "DIM5 + DIM6 (side walls) must be smaller than the width DIM1");
      break;
    case SectionShape::Cross:
    case SectionShape::H:
      need(s, d[3] < d[2], "DIM4 must be smaller than DIM3");
      break;
    case SectionShape::Hexa:
      need(s, 2 * d[0] < d[1], "2*DIM1 (the tips) must be smaller than the width DIM2");
      break;
    case SectionShape::Hat:
      need(s, 2 * d[1] < d[0], "2*DIM2 must be smaller than the height DIM1");
      need(s, 2 * d[1] < d[2], "2*DIM2 must be smaller than the top width DIM3");
      break;
    case SectionShape::Hat1:
      need(s, d[3] + d[4] < d[1] && 2 * d[3] + d[4] < d[1], "DIM5 + 2*DIM4 must be smaller than the height DIM2");
      need(s, 2 * d[3] < d[2] && d[2] < d[0], "2*DIM4 < DIM3 < DIM1 must hold (hat top inside the base)");
      break;
    case SectionShape::DBox:
      need(s, d[2] < d[0], "DIM3 (left cell) must be smaller than the width DIM1");
      need(s, d[3] + d[4] / 2 < d[2], "DIM4 + DIM5/2 must be smaller than DIM3 (left cell open)");
      need(s, d[2] + d[4] / 2 + d[5] < d[0], "DIM3 + DIM5/2 + DIM6 must be smaller than DIM1 (right cell open)");
      need(s, d[6] + d[7] < d[1] && d[8] + d[9] < d[1], "DIM7 + DIM8 and DIM9 + DIM10 must be smaller than DIM2");
      break;
    default: break;
  }
}

/// First and second area moments of a section about the figure's origin,
/// accumulated over signed polygons (holes subtract):
///   a = ∫dA, sy = ∫y dA, sz = ∫z dA, yy = ∫y² dA, zz = ∫z² dA, yz = ∫yz dA.
template <class T>
struct Moments {
  T a{0}, sy{0}, sz{0}, yy{0}, zz{0}, yz{0};

  /// Polygon with vertices (z_k, y_k) counter-clockwise in the (z, y) plane;
  /// Green's theorem per edge (the shoelace family of formulas).
  void polygon(const std::vector<std::array<T, 2>>& p, double sign = 1.0) {
    const std::size_t n = p.size();
    for (std::size_t k = 0; k < n; ++k) {
      const T z0 = p[k][0], y0 = p[k][1], z1 = p[(k + 1) % n][0], y1 = p[(k + 1) % n][1];
      const T c = sign * (z0 * y1 - z1 * y0);
      a += c / 2.0;
      sz += c * (z0 + z1) / 6.0;
      sy += c * (y0 + y1) / 6.0;
      zz += c * (z0 * z0 + z0 * z1 + z1 * z1) / 12.0;
      yy += c * (y0 * y0 + y0 * y1 + y1 * y1) / 12.0;
      yz += c * (z0 * y1 + 2.0 * z0 * y0 + 2.0 * z1 * y1 + z1 * y0) / 24.0;
    }
  }
  /// Axis-parallel rectangle z ∈ [z0, z1], y ∈ [y0, y1].
  void rect(T z0, T z1, T y0, T y1, double sign = 1.0) {
    polygon({{z0, y0}, {z1, y0}, {z1, y1}, {z0, y1}}, sign);
  }
  /// (A, I1, I2, I12) about the centroid: I1 = ∫y², I2 = ∫z², I12 = ∫yz.
  std::array<T, 4> central() const {
    const T yc = sy / a, zc = sz / a;
    return {a, yy - a * yc * yc, zz - a * zc * zc, yz - a * yc * zc};
  }
};

/// The section's values from its moments, J and the shear areas of planes 1
/// and 2 (K = shear area / A). `symmetric`: the section has an axis of symmetry
/// along y or z, so I12 is exactly 0 (set, not left to rounding).
template <class T>
std::array<T, kSectionValues> result(const Moments<T>& m, T j, T k1_area, T k2_area, bool symmetric = true) {
  const auto c = m.central();
  return {c[0], c[1], c[2], symmetric ? T(0) : c[3], j, k1_area / c[0], k2_area / c[0]};
}

/// Bredt–Batho single cell: J = 4 A_m² / ∮ ds/t.
template <class T>
T bredt(T area_mid, T ds_over_t) {
  return 4.0 * area_mid * area_mid / ds_over_t;
}

/// (A, I1, I2, I12, J, K1, K2) for scalar T (double or complex for the complex
/// step), each type as section.hpp states it.
template <class T>
std::array<T, kSectionValues> props(SectionShape s, const std::vector<T>& d) {
  const double pi = M_PI;
  Moments<T> m;
  switch (s) {
    case SectionShape::Rod: {
      const T r2 = d[0] * d[0];
      return {pi * r2, pi * r2 * r2 / 4.0, pi * r2 * r2 / 4.0, T(0), pi * r2 * r2 / 2.0, T(0.9), T(0.9)};
    }
    case SectionShape::Tube:
    case SectionShape::Tube2: {
      const T ri = s == SectionShape::Tube ? d[1] : d[0] - d[1];
      const T ro2 = d[0] * d[0], ri2 = ri * ri;
      const T i = pi * (ro2 * ro2 - ri2 * ri2) / 4.0;
      return {pi * (ro2 - ri2), i, i, T(0), 2.0 * i, T(0.5), T(0.5)};
    }
    case SectionShape::Bar: {
      const T b = d[0], h = d[1];
      const bool wide = real_part(b) >= real_part(h);
      const T a = wide ? b : h, c = wide ? h : b;
      const T ca = c / a;
      const T j = a * c * c * c * (1.0 / 3.0 - 0.21 * ca * (1.0 - ca * ca * ca * ca / 12.0));
      return {b * h, b * h * h * h / 12.0, h * b * b * b / 12.0, T(0), j, T(5.0 / 6.0), T(5.0 / 6.0)};
    }
    case SectionShape::Box: {
      const T b = d[0], h = d[1], ty = d[2], tz = d[3];
      m.rect(-b / 2.0, b / 2.0, -h / 2.0, h / 2.0);
      m.rect(-b / 2.0 + tz, b / 2.0 - tz, -h / 2.0 + ty, h / 2.0 - ty, -1.0);
      const T j = bredt<T>((b - tz) * (h - ty), 2.0 * (b - tz) / ty + 2.0 * (h - ty) / tz);
      return result<T>(m, j, 2.0 * (h - 2.0 * ty) * tz, 2.0 * (b - 2.0 * tz) * ty);
    }
    case SectionShape::Box1: {
      // DIM3 top (+y), DIM4 bottom, DIM5 left (−z), DIM6 right wall.
      const T b = d[0], h = d[1], tt = d[2], tb = d[3], tl = d[4], tr = d[5];
      m.rect(T(0), b, T(0), h);
      m.rect(tl, b - tr, tb, h - tt, -1.0);
      const T bm = b - (tl + tr) / 2.0, hm = h - (tt + tb) / 2.0;
      const T j = bredt<T>(bm * hm, bm / tt + bm / tb + hm / tl + hm / tr);
      return result<T>(m, j, (h - tt - tb) * (tl + tr), (b - tl - tr) * (tt + tb), false);
    }
    case SectionShape::DBox: {
      // Two cells side by side; DIM3 from the left edge to the middle wall's centre line.
      const T b = d[0], h = d[1], bl = d[2], tl = d[3], tm = d[4], tr = d[5];
      const T ttl = d[6], tbl = d[7], ttr = d[8], tbr = d[9];
      m.rect(T(0), b, T(0), h);
      m.rect(tl, bl - tm / 2.0, tbl, h - ttl, -1.0);
      m.rect(bl + tm / 2.0, b - tr, tbr, h - ttr, -1.0);
      // Two-cell Bredt: [a11 −a12; −a12 a22] q = 2 G θ [A1; A2], J = 2 (A1 q1 + A2 q2) / (G θ).
      const T b1 = bl - tl / 2.0, h1 = h - (ttl + tbl) / 2.0;
      const T b2 = b - bl - tr / 2.0, h2 = h - (ttr + tbr) / 2.0;
      const T hmid = (h1 + h2) / 2.0;
      const T a1 = b1 * h1, a2 = b2 * h2;
      const T a12 = hmid / tm;
      const T a11 = b1 / ttl + b1 / tbl + h1 / tl + a12, a22 = b2 / ttr + b2 / tbr + h2 / tr + a12;
      const T det = a11 * a22 - a12 * a12;
      const T q1 = 2.0 * (a22 * a1 + a12 * a2) / det, q2 = 2.0 * (a12 * a1 + a11 * a2) / det;
      const T j = 2.0 * (a1 * q1 + a2 * q2);
      const T k1 = tl * (h - ttl - tbl) + tm * (h - (ttl + tbl + ttr + tbr) / 2.0) + tr * (h - ttr - tbr);
      const T k2 = (bl - tl - tm / 2.0) * (ttl + tbl) + (b - bl - tm / 2.0 - tr) * (ttr + tbr);
      return result<T>(m, j, k1, k2, false);
    }
    case SectionShape::I: {
      const T h = d[0], bb = d[1], bt = d[2], tw = d[3], tb = d[4], tt = d[5];
      const T hw = h - tb - tt;
      m.rect(-bb / 2.0, bb / 2.0, T(0), tb);
      m.rect(-tw / 2.0, tw / 2.0, tb, h - tt);
      m.rect(-bt / 2.0, bt / 2.0, h - tt, h);
      const T j = (bb * tb * tb * tb + bt * tt * tt * tt + (h - (tb + tt) / 2.0) * tw * tw * tw) / 3.0;
      return result<T>(m, j, hw * tw, bb * tb + bt * tt);
    }
    case SectionShape::I1: {
      const T bo = d[0], tw = d[1], hw = d[2], h = d[3];
      const T tf = (h - hw) / 2.0, b = bo + tw;
      m.rect(-b / 2.0, b / 2.0, -h / 2.0, -hw / 2.0);
      m.rect(-tw / 2.0, tw / 2.0, -hw / 2.0, hw / 2.0);
      m.rect(-b / 2.0, b / 2.0, hw / 2.0, h / 2.0);
      const T j = (2.0 * b * tf * tf * tf + (h - tf) * tw * tw * tw) / 3.0;
      return result<T>(m, j, hw * tw, 2.0 * b * tf);
    }
    case SectionShape::Chan: {
      // Web at the left (z from 0 to DIM3), flanges to +z.
      const T b = d[0], h = d[1], tw = d[2], tf = d[3];
      m.rect(T(0), tw, T(0), h);
      m.rect(tw, b, T(0), tf);
      m.rect(tw, b, h - tf, h);
      const T j = (2.0 * (b - tw / 2.0) * tf * tf * tf + (h - tf) * tw * tw * tw) / 3.0;
      return result<T>(m, j, (h - 2.0 * tf) * tw, 2.0 * (b - tw) * tf);
    }
    case SectionShape::Chan1: {
      const T bo = d[0], tw = d[1], hw = d[2], h = d[3];
      const T tf = (h - hw) / 2.0;
      m.rect(T(0), tw, T(0), h);
      m.rect(tw, tw + bo, T(0), tf);
      m.rect(tw, tw + bo, h - tf, h);
      const T j = (2.0 * (bo + tw / 2.0) * tf * tf * tf + (h - tf) * tw * tw * tw) / 3.0;
      return result<T>(m, j, hw * tw, 2.0 * bo * tf);
    }
    case SectionShape::Chan2: {
      // U open upwards: base DIM4 wide and DIM2 thick, legs DIM1 thick and DIM3 high.
      const T tl = d[0], tb = d[1], h = d[2], b = d[3];
      m.rect(T(0), tl, T(0), h);
      m.rect(b - tl, b, T(0), h);
      m.rect(tl, b - tl, T(0), tb);
      const T j = (2.0 * (h - tb / 2.0) * tl * tl * tl + (b - tl) * tb * tb * tb) / 3.0;
      return result<T>(m, j, 2.0 * (h - tb) * tl, (b - 2.0 * tl) * tb);
    }
    case SectionShape::T:
    case SectionShape::T2: {
      // T: flange on top; T2: flange at the bottom (the same properties).
      const T b = d[0], h = d[1], tf = d[2], tw = d[3];
      m.rect(-b / 2.0, b / 2.0, h - tf, h);
      m.rect(-tw / 2.0, tw / 2.0, T(0), h - tf);
      const T j = (b * tf * tf * tf + (h - tf / 2.0) * tw * tw * tw) / 3.0;
      return result<T>(m, j, (h - tf) * tw, b * tf);
    }
    case SectionShape::T1: {
      // Flange upright (DIM1 high, DIM3 thick), web DIM2 long and DIM4 thick to +z.
      const T hf = d[0], bw = d[1], tf = d[2], tw = d[3];
      m.rect(T(0), tf, -hf / 2.0, hf / 2.0);
      m.rect(tf, tf + bw, -tw / 2.0, tw / 2.0);
      const T j = (hf * tf * tf * tf + (bw + tf / 2.0) * tw * tw * tw) / 3.0;
      return result<T>(m, j, hf * tf, bw * tw);
    }
    case SectionShape::L: {
      // Legs from the corner along +z (DIM1 wide, DIM3 thick) and +y (DIM2 high, DIM4 thick).
      const T b = d[0], h = d[1], t1 = d[2], t2 = d[3];
      m.rect(T(0), b, T(0), t1);
      m.rect(T(0), t2, t1, h);
      const T j = ((b - t2 / 2.0) * t1 * t1 * t1 + (h - t1 / 2.0) * t2 * t2 * t2) / 3.0;
      return result<T>(m, j, (h - t1) * t2, (b - t2) * t1, false);
    }
    case SectionShape::Cross: {
      // Upright bar DIM2 wide, DIM3 high; arms DIM1/2 long each side, DIM4 thick.
      const T arms = d[0], tv = d[1], hv = d[2], th = d[3];
      m.rect(-tv / 2.0, tv / 2.0, -hv / 2.0, hv / 2.0);
      m.rect(-tv / 2.0 - arms / 2.0, -tv / 2.0, -th / 2.0, th / 2.0);
      m.rect(tv / 2.0, tv / 2.0 + arms / 2.0, -th / 2.0, th / 2.0);
      const T j = (hv * tv * tv * tv + (arms + tv) * th * th * th) / 3.0;
      return result<T>(m, j, hv * tv, arms * th);
    }
    case SectionShape::H: {
      // Two upright legs DIM2/2 thick and DIM3 high, DIM1 apart; web DIM4 thick between them.
      const T gap = d[0], tl2 = d[1], hl = d[2], tw = d[3];
      const T tl = tl2 / 2.0;
      m.rect(-gap / 2.0 - tl, -gap / 2.0, -hl / 2.0, hl / 2.0);
      m.rect(gap / 2.0, gap / 2.0 + tl, -hl / 2.0, hl / 2.0);
      m.rect(-gap / 2.0, gap / 2.0, -tw / 2.0, tw / 2.0);
      const T j = (2.0 * hl * tl * tl * tl + (gap + tl) * tw * tw * tw) / 3.0;
      return result<T>(m, j, 2.0 * hl * tl, gap * tw);
    }
    case SectionShape::Z: {
      // Web centred; top flange to −z, bottom flange to +z.
      const T bo = d[0], tw = d[1], hw = d[2], h = d[3];
      const T tf = (h - hw) / 2.0;
      m.rect(-tw / 2.0, tw / 2.0, -hw / 2.0, hw / 2.0);
      m.rect(-tw / 2.0 - bo, tw / 2.0, hw / 2.0, h / 2.0);
      m.rect(-tw / 2.0, tw / 2.0 + bo, -h / 2.0, -hw / 2.0);
      const T j = (2.0 * (bo + tw / 2.0) * tf * tf * tf + (h - tf) * tw * tw * tw) / 3.0;
      return result<T>(m, j, hw * tw, 2.0 * bo * tf, false);
    }
    case SectionShape::Hexa: {
      // Width DIM2 along z with tips DIM1 long at mid-height, height DIM3.
      const T c = d[0], w = d[1], h = d[2];
      m.polygon({{-w / 2.0, T(0)}, {-w / 2.0 + c, -h / 2.0}, {w / 2.0 - c, -h / 2.0},
                 {w / 2.0, T(0)}, {w / 2.0 - c, h / 2.0}, {-w / 2.0 + c, h / 2.0}});
      const auto cm = m.central();
      // Saint-Venant's approximation J = A⁴ / (4π² I_p) (exact for the ellipse).
      const T j = cm[0] * cm[0] * cm[0] * cm[0] / (4.0 * pi * pi * (cm[1] + cm[2]));
      return {cm[0], cm[1], cm[2], T(0), j, T(5.0 / 6.0), T(5.0 / 6.0)};
    }
    case SectionShape::Hat: {
      // Top DIM3 wide, webs down to lips DIM4 wide at the bottom; one thickness DIM2.
      const T h = d[0], t = d[1], bt = d[2], bl = d[3];
      m.rect(-bt / 2.0, bt / 2.0, h - t, h);
      m.rect(-bt / 2.0, -bt / 2.0 + t, T(0), h - t);
      m.rect(bt / 2.0 - t, bt / 2.0, T(0), h - t);
      m.rect(-bt / 2.0 - bl, -bt / 2.0, T(0), t);
      m.rect(bt / 2.0, bt / 2.0 + bl, T(0), t);
      const T j = ((bt - t) + 2.0 * (h - t) + 2.0 * (bl + t / 2.0)) * t * t * t / 3.0;
      return result<T>(m, j, 2.0 * (h - 2.0 * t) * t, (bt - 2.0 * t) * t + 2.0 * bl * t);
    }
    case SectionShape::Hat1: {
      // Base plate DIM1 × DIM5 at the bottom, a hat (top DIM3 wide, thickness DIM4) on it,
      // its lips running out to the plate's edges; overall height DIM2.
      const T b = d[0], h = d[1], bt = d[2], t = d[3], tp = d[4];
      m.rect(-b / 2.0, b / 2.0, T(0), tp);
      m.rect(-b / 2.0, -bt / 2.0, tp, tp + t);
      m.rect(bt / 2.0, b / 2.0, tp, tp + t);
      m.rect(-bt / 2.0, -bt / 2.0 + t, tp, h - t);
      m.rect(bt / 2.0 - t, bt / 2.0, tp, h - t);
      m.rect(-bt / 2.0, bt / 2.0, h - t, h);
      // Closed cell (hat and plate) by Bredt, plus the open outstands (plate and lip together).
      const T bm = bt - t, hm = h - t / 2.0 - tp / 2.0;
      const T tout = t + tp;
      const T j = bredt<T>(bm * hm, bm / t + bm / tp + 2.0 * hm / t) + (b - bt) * tout * tout * tout / 3.0;
      return result<T>(m, j, 2.0 * (h - tp - 2.0 * t) * t, b * tp + (bt - 2.0 * t) * t + (b - bt) * t);
    }
  }
  return {};
}
}  // namespace

SectionShape parse_section_shape(const std::string& type) {
  for (std::size_t k = 0; k < std::size(kShapes); ++k)
    if (type == kShapes[k].name) return static_cast<SectionShape>(k);
  throw std::invalid_argument("PBARL/PBEAML TYPE \"" + type + "\" is not supported (expected " +
                              supported_section_types() + ")");
}

std::string supported_section_types() {
  std::string s;
  for (std::size_t k = 0; k < std::size(kShapes); ++k) s += (k ? ", " : "") + std::string(kShapes[k].name);
  return s;
}

const char* section_shape_name(SectionShape s) { return kShapes[static_cast<int>(s)].name; }

int section_dim_count(SectionShape s) { return kShapes[static_cast<int>(s)].dims; }

bool shear_centre_at_centroid(SectionShape s, const std::vector<double>& d) {
  switch (s) {
    case SectionShape::Rod:
    case SectionShape::Tube:
    case SectionShape::Tube2:
    case SectionShape::Bar:
    case SectionShape::Box:
    case SectionShape::I1:
    case SectionShape::Cross:
    case SectionShape::H:
    case SectionShape::Z:
    case SectionShape::Hexa: return true;
    case SectionShape::I: return d.size() == 6 && d[1] == d[2] && d[4] == d[5];
    case SectionShape::Box1: return d.size() == 6 && d[2] == d[3] && d[4] == d[5];
    default: return false;
  }
}

SectionProperties section_properties(SectionShape s, const std::vector<double>& dims) {
  check_dims(s, dims);
  const auto p = props<double>(s, dims);
  return {p[0], p[1], p[2], p[3], p[4], p[5], p[6]};
}

Eigen::Matrix<double, kSectionValues, Eigen::Dynamic> section_jacobian(SectionShape s,
                                                                     const std::vector<double>& dims) {
  check_dims(s, dims);
  Eigen::Matrix<double, kSectionValues, Eigen::Dynamic> jac(kSectionValues, dims.size());
  for (std::size_t k = 0; k < dims.size(); ++k) {
    std::vector<detail::Complex> d(dims.begin(), dims.end());
    d[k] += detail::Complex(0.0, detail::kComplexStep);
    const auto p = props<detail::Complex>(s, d);
    for (int r = 0; r < kSectionValues; ++r) jac(r, k) = p[r].imag() / detail::kComplexStep;
  }
  return jac;
}

}  // namespace ssid::translators::elements
