#include "translators/elements/section.hpp"

#include <array>
#include <cmath>
#include <stdexcept>

#include "translators/elements/complex_step.hpp"

namespace ssid::translators::elements {

namespace {
using detail::real_part;

std::invalid_argument bad(SectionShape s, const std::string& what) {
  return std::invalid_argument(std::string("PBARL/PBEAML TYPE=") + section_shape_name(s) + ": " + what);
}

void check_dims(SectionShape s, const std::vector<double>& d) {
  if (static_cast<int>(d.size()) != section_dim_count(s))
    throw bad(s, "expected " + std::to_string(section_dim_count(s)) + " dimensions, got " +
                     std::to_string(d.size()));
  for (std::size_t i = 0; i < d.size(); ++i)
    if (!(d[i] > 0.0)) throw bad(s, "DIM" + std::to_string(i + 1) + " must be > 0, got " + std::to_string(d[i]));
  switch (s) {
    case SectionShape::Tube:
      if (d[1] >= d[0]) throw bad(s, "inner radius DIM2 must be smaller than outer radius DIM1");
      break;
    case SectionShape::Box:
      if (2 * d[2] >= d[1]) throw bad(s, "2*DIM3 (top/bottom walls) must be smaller than the height DIM2");
      if (2 * d[3] >= d[0]) throw bad(s, "2*DIM4 (side walls) must be smaller than the width DIM1");
      break;
    case SectionShape::I:
      if (d[4] + d[5] >= d[0]) throw bad(s, "flange thicknesses DIM5 + DIM6 must be smaller than the depth DIM1");
      break;
    default: break;
  }
}

/// (A, I1, I2, I12, J, K1, K2) for scalar T (double or complex for the complex
/// step); the shear factors as section.hpp states them.
template <class T>
std::array<T, kSectionValues> props(SectionShape s, const std::vector<T>& d) {
  const double pi = M_PI;
  switch (s) {
    case SectionShape::Rod: {
      const T r2 = d[0] * d[0];
      return {pi * r2, pi * r2 * r2 / 4.0, pi * r2 * r2 / 4.0, T(0), pi * r2 * r2 / 2.0, T(0.9), T(0.9)};
    }
    case SectionShape::Tube: {
      const T ro2 = d[0] * d[0], ri2 = d[1] * d[1];
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
      const T bi = b - 2.0 * tz, hi = h - 2.0 * ty;
      const T j = 2.0 * ty * tz * (b - tz) * (b - tz) * (h - ty) * (h - ty) / (b * tz + h * ty - tz * tz - ty * ty);
      const T a = b * h - bi * hi;
      return {a, (b * h * h * h - bi * hi * hi * hi) / 12.0, (h * b * b * b - hi * bi * bi * bi) / 12.0,
              T(0), j, 2.0 * hi * tz / a, 2.0 * bi * ty / a};
    }
    case SectionShape::I: {
      const T h = d[0], bb = d[1], bt = d[2], tw = d[3], tb = d[4], tt = d[5];
      const T hw = h - tb - tt;
      const T ab = bb * tb, aw = tw * hw, at = bt * tt;
      const T a = ab + aw + at;
      // Centroid height above the bottom face.
      const T yb = tb / 2.0, yw = tb + hw / 2.0, yt = h - tt / 2.0;
      const T yc = (ab * yb + aw * yw + at * yt) / a;
      const T i1 = bb * tb * tb * tb / 12.0 + ab * (yb - yc) * (yb - yc) + tw * hw * hw * hw / 12.0 +
                   aw * (yw - yc) * (yw - yc) + bt * tt * tt * tt / 12.0 + at * (yt - yc) * (yt - yc);
      const T i2 = (tb * bb * bb * bb + hw * tw * tw * tw + tt * bt * bt * bt) / 12.0;
      const T j = (bb * tb * tb * tb + bt * tt * tt * tt + hw * tw * tw * tw) / 3.0;
      return {a, i1, i2, T(0), j, aw / a, (ab + at) / a};
    }
  }
  return {};
}
}  // namespace

SectionShape parse_section_shape(const std::string& type) {
  if (type == "ROD") return SectionShape::Rod;
  if (type == "TUBE") return SectionShape::Tube;
  if (type == "BAR") return SectionShape::Bar;
  if (type == "BOX") return SectionShape::Box;
  if (type == "I") return SectionShape::I;
  throw std::invalid_argument("PBARL/PBEAML TYPE \"" + type + "\" is not supported (expected ROD, TUBE, BAR, BOX or I)");
}

const char* section_shape_name(SectionShape s) {
  static const char* names[] = {"ROD", "TUBE", "BAR", "BOX", "I"};
  return names[static_cast<int>(s)];
}

int section_dim_count(SectionShape s) {
  static const int n[] = {1, 2, 2, 4, 6};
  return n[static_cast<int>(s)];
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
