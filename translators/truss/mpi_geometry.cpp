/// \file mpi_geometry.cpp
/// Lays out the MPI-like truss. Every number here is a choice documented in
/// docs/truss.md; the report gives the overall size (7 m x 6.3 m x 5.5 m),
/// the mass (210 kg), 80 balls, about 250 struts and the joint parameters.
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

#include "translators/truss/configurations.hpp"
#include "translators/truss/truss_model.hpp"

namespace ssid::translators::truss {

namespace {

constexpr double kInch = 0.0254;
constexpr double kInch2 = kInch * kInch;
constexpr double kInch4 = kInch2 * kInch2;

/// Rounds to `digits` significant digits so every value prints exactly in an
/// 8-character NASTRAN field and the inventory equals what the deck says.
double sig(double v, int digits = 4) {
  if (v == 0) return 0;
  const double p = std::pow(10.0, digits - 1 - static_cast<int>(std::floor(std::log10(std::fabs(v)))));
  return std::round(v * p) / p;
}
/// Rounds a coordinate to 0.1 mm.
double mm10(double v) { return std::round(v * 1e4) / 1e4; }

struct Builder {
  TrussModel t;
  int add_ball(const Eigen::Vector3d& x, const std::string& group, const std::string& label) {
    Ball b;
    b.id = static_cast<int>(t.balls.size()) + 1;
    b.x = Eigen::Vector3d(mm10(x.x()), mm10(x.y()), mm10(x.z()));
    b.group = group;
    b.label = label;
    t.balls.push_back(b);
    return b.id;
  }
  void add_member(int a, int b, const std::string& group, const std::string& role) {
    Member m;
    m.id = static_cast<int>(t.members.size()) + 1;
    m.a = a;
    m.b = b;
    m.group = group;
    m.role = role;
    t.members.push_back(m);
  }
  /// A square-section boom from station rings `ring[s][c]` (corner c = 0..3 around the section):
  /// longerons, battens, one diagonal per side face per bay (alternating), one section diagonal per station.
  void add_boom(const std::vector<std::array<int, 4>>& ring, const std::string& group, bool section_diagonals,
                std::size_t first_batten_station, std::size_t last_batten_station, const std::string& diagonal_role) {
    for (std::size_t s = 0; s < ring.size(); ++s) {
      if (s >= first_batten_station && s <= last_batten_station) {
        for (int c = 0; c < 4; ++c) add_member(ring[s][c], ring[s][(c + 1) % 4], group, "batten");
        if (section_diagonals) add_member(ring[s][0], ring[s][2], group, "section_diagonal");
      }
      if (s + 1 == ring.size()) continue;
      for (int c = 0; c < 4; ++c) add_member(ring[s][c], ring[s + 1][c], group, "longeron");
      for (int c = 0; c < 4; ++c) {
        const int c2 = (c + 1) % 4;
        // Alternate the diagonal direction bay by bay (a zig-zag along each face).
        if ((s + c) % 2 == 0)
          add_member(ring[s][c], ring[s + 1][c2], group, diagonal_role);
        else
          add_member(ring[s][c2], ring[s + 1][c], group, diagonal_role);
      }
    }
  }
};

}  // namespace

Hardware mpi_hardware() {
  Hardware h;
  h.E = 68.9e9;  // 6061-T6 drawn tube
  h.nu = 0.33;
  h.rho = 2700.0;
  h.tube_od = 0.03175;                 // 1.25 in
  h.tube_area = sig(0.3123 * kInch2);  // A_strut, report Table 2 final (in^2 -> m^2)
  const double id2 = h.tube_od * h.tube_od - 4.0 * h.tube_area / M_PI;
  h.tube_inertia = sig(M_PI / 64.0 * (std::pow(h.tube_od, 4) - id2 * id2));
  h.bnut = {0.0127, sig(0.0672 * kInch2), sig(4.01e-4 * kInch4), 0.045};    // A_bnut, I_bnut final
  h.endcap = {0.040, 3.0e-4, sig(0.00856 * kInch4), 0.060};                // I_endcap final
  h.long_bnut = {sig(3.1 * kInch, 3), sig(0.0672 * kInch2), sig(3.77e-4 * kInch4), 0.118};  // Table 3, 3.1 in
  h.ball_radius = 0.040;
  h.ball_mass = 0.73;
  return h;
}

double TrussModel::tube_length(const Member& m) const {
  return length(m) - 2.0 * (hw.ball_radius + hw.endcap.length + bnut_of(m).length);
}

double TrussModel::member_mass(const Member& m) const {
  return tube_length(m) * hw.tube_mass_per_length() + 2.0 * hw.endcap.mass + 2.0 * bnut_of(m).mass + m.mid_mass;
}

double TrussModel::total_mass() const {
  double s = 0;
  for (const auto& b : balls) s += hw.ball_mass + b.added_mass;
  for (const auto& m : members) s += member_mass(m);
  return s;
}

Eigen::Vector3d TrussModel::center_of_gravity() const {
  Eigen::Vector3d s = Eigen::Vector3d::Zero();
  for (const auto& b : balls) s += (hw.ball_mass + b.added_mass) * b.x;
  // A strut's hardware is symmetric about its mid-point (both ends alike), so its
  // mass acts there; a long B-nut strut has long B-nuts at both ends.
  for (const auto& m : members) s += member_mass(m) * 0.5 * (ball(m.a).x + ball(m.b).x);
  return s / total_mass();
}

Eigen::Vector3d TrussModel::extent() const {
  Eigen::Vector3d lo = balls.front().x, hi = lo;
  for (const auto& b : balls) {
    lo = lo.cwiseMin(b.x);
    hi = hi.cwiseMax(b.x);
  }
  return hi - lo;
}

std::size_t TrussModel::count_members(const std::string& role, const std::string& group) const {
  return static_cast<std::size_t>(std::count_if(members.begin(), members.end(), [&](const Member& m) {
    return (role.empty() || m.role == role) && (group.empty() || m.group == group);
  }));
}

TrussModel build_mpi(const MpiLayout& L) {
  Builder B;
  B.t.name = "mpi";
  B.t.hw = mpi_hardware();
  const int s0 = L.tower_station;            // optics station where the tower bay starts
  const int m0 = L.metrology_tower_station;  // metrology station where the tower bay starts
  const double wx = L.tower_width_x, wy = L.tower_width_y;
  const double bo = (L.optics_length - wx) / (L.optics_bays - 1);        // optics bays other than the tower's
  const double bm = (L.metrology_length - wy) / (L.metrology_bays - 1);  // metrology bays other than the tower's
  auto optics_x = [&](int s) { return s <= s0 ? s * bo : s0 * bo + wx + (s - s0 - 1) * bo; };
  auto metrology_y = [&](int s) { return s <= m0 ? (s - m0) * bm : wy + (s - m0 - 1) * bm; };

  // Optics boom: stations along x, corners (y, z) = (0,0) (wy,0) (wy,H) (0,H).
  std::vector<std::array<int, 4>> optics(static_cast<std::size_t>(L.optics_bays + 1));
  const double corner_y[4] = {0.0, wy, wy, 0.0};
  const double corner_z[4] = {0.0, 0.0, L.optics_depth, L.optics_depth};
  for (int s = 0; s <= L.optics_bays; ++s)
    for (int c = 0; c < 4; ++c)
      optics[s][c] = B.add_ball({optics_x(s), corner_y[c], corner_z[c]}, "optics_boom",
                                "O" + std::to_string(s) + "-" + std::to_string(c));

  // Tower: base ring = the optics top balls of the tower bay; corners (x, y) =
  // (x0,0) (x1,0) (x1,wy) (x0,wy). Intermediate rings every h_t; top ring = metrology bottom balls.
  const double tower_height = L.overall_height - L.optics_depth - L.metrology_depth;
  const double h_t = tower_height / L.tower_bays;
  std::vector<std::array<int, 4>> tower(static_cast<std::size_t>(L.tower_bays + 1));
  tower[0] = {optics[s0][3], optics[s0 + 1][3], optics[s0 + 1][2], optics[s0][2]};
  const double x0 = optics_x(s0), x1 = optics_x(s0 + 1);
  const double tx[4] = {x0, x1, x1, x0};
  const double ty[4] = {0.0, 0.0, wy, wy};
  for (int k = 1; k < L.tower_bays; ++k)
    for (int c = 0; c < 4; ++c)
      tower[k][c] = B.add_ball({tx[c], ty[c], L.optics_depth + k * h_t}, "tower",
                               "T" + std::to_string(k) + "-" + std::to_string(c));

  // Metrology boom along y, tilted about x through the middle of the tower top so
  // the long arm rises: the boom is perpendicular to the optics boom and at a
  // slightly acute angle (90 - tilt degrees) with the tower.
  const double zb = L.optics_depth + tower_height;
  const double tilt = L.metrology_tilt_deg * M_PI / 180.0;
  const double py = 0.5 * wy;
  const double mx[4] = {x0, x1, x1, x0};
  const double mz[4] = {0.0, 0.0, L.metrology_depth, L.metrology_depth};
  std::vector<std::array<int, 4>> metrology(static_cast<std::size_t>(L.metrology_bays + 1));
  for (int s = 0; s <= L.metrology_bays; ++s)
    for (int c = 0; c < 4; ++c) {
      const double y = metrology_y(s) - py;
      const double z = mz[c];
      const Eigen::Vector3d x(mx[c], py + y * std::cos(tilt) - z * std::sin(tilt), zb + y * std::sin(tilt) + z * std::cos(tilt));
      metrology[s][c] = B.add_ball(x, "metrology_boom", "M" + std::to_string(s) + "-" + std::to_string(c));
    }
  tower[L.tower_bays] = {metrology[m0][0], metrology[m0][1], metrology[m0 + 1][1], metrology[m0 + 1][0]};

  B.add_boom(optics, "optics_boom", true, 0, L.optics_bays, "diagonal");
  B.add_boom(metrology, "metrology_boom", true, 0, L.metrology_bays, "diagonal");
  // The tower's end rings are optics and metrology faces (already braced): only its intermediate rings get battens.
  B.add_boom(tower, "tower", true, 1, L.tower_bays - 1, "tower_diagonal");

  // Three suspension points: two on the optics boom (top, y = 0 side), one on the metrology boom's long arm.
  TrussModel& t = B.t;
  const int p1 = optics[1][3], p2 = optics[L.optics_bays - 1][3], p3 = metrology[L.metrology_bays - 1][3];
  t.suspension = {{p1}, {p2}, {p3}};
  set_suspension(t, false);
  return std::move(B.t);
}

std::vector<int> metrology_tip_balls(const TrussModel& t) {
  std::vector<int> ids;
  for (const auto& b : t.balls)
    if (b.label.rfind("M" + std::to_string(MpiLayout{}.metrology_bays) + "-", 0) == 0) ids.push_back(b.id);
  return ids;
}

std::vector<int> optics_tip_balls(const TrussModel& t) {
  std::vector<int> ids;
  for (const auto& b : t.balls)
    if (b.label.rfind("O" + std::to_string(MpiLayout{}.optics_bays) + "-", 0) == 0) ids.push_back(b.id);
  return ids;
}

int longest_member(const TrussModel& t) {
  int best = 0;
  double len = -1;
  for (const auto& m : t.members)
    if (t.length(m) > len + 1e-12) {
      len = t.length(m);
      best = m.id;
    }
  return best;
}

}  // namespace ssid::translators::truss
