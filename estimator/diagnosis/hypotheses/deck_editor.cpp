#include <algorithm>
#include <cctype>
#include <stdexcept>

#include "formats/card_traits.hpp"
#include "formats/deck_writer.hpp"
#include "formats/parse_error.hpp"
#include "estimator/diagnosis/hypotheses/model_extension.hpp"

namespace ssid::estimator::diagnosis::hypotheses {

namespace {

/// The first id above `current_max`, rounded up to a multiple of 1000 so
/// generated cards stand out (9001, 9002, … after ids up to 8999).
std::int64_t fresh(std::int64_t current_max) {
  return (current_max / 1000 + 1) * 1000 + 1;
}

}  // namespace

DeckEditor::DeckEditor(const std::string& text, const std::string& name)
    : m_deck(std::make_unique<formats::Deck>(formats::read_deck_text(text, name))) {
  m_bulk = formats::parse_bulk(*m_deck);
  formats::resolve(*m_deck, m_bulk);
  // The largest id of each kind, over the id spaces of the card traits: every
  // element family shares one counter (generated ids stay unique across them).
  std::int64_t g = 0, e = 0, p = 0, d = 0, r = 0, c = 0, m = 0;
  for (const formats::CardTraits& t : formats::card_traits()) {
    if (!t.each_id) continue;
    std::int64_t* counter = nullptr;
    switch (t.space) {
      case formats::IdSpace::GridPoint: counter = &g; break;
      case formats::IdSpace::Element:
      case formats::IdSpace::MassElement:
      case formats::IdSpace::RigidElement: counter = &e; break;
      case formats::IdSpace::Property: counter = &p; break;
      case formats::IdSpace::Desvar: counter = &d; break;
      case formats::IdSpace::Dvprel:
      case formats::IdSpace::Dvmrel: counter = &r; break;
      case formats::IdSpace::CoordinateSystem: counter = &c; break;
      case formats::IdSpace::Material: counter = &m; break;
      default: break;
    }
    if (counter) t.each_id(m_bulk, [counter](std::int64_t id, std::size_t) { *counter = std::max(*counter, id); });
  }
  for (auto id : m_bulk.implied_spoints) g = std::max(g, id);
  m_next_grid = fresh(g);
  m_next_element = fresh(e);
  m_next_property = fresh(p);
  m_next_desvar = fresh(d);
  m_next_relation = fresh(r);
  m_next_coord = fresh(c);
  m_next_material = fresh(m);
}

void DeckEditor::append(const std::vector<formats::FieldValue>& values) {
  const auto& name = std::get<std::string>(values.at(0));
  m_appended += formats::format_card(name, values, formats::FieldFormat::Small);
}

void DeckEditor::comment(const std::string& text) { m_appended += "$ " + text + "\n"; }

void DeckEditor::change(std::size_t card, std::vector<formats::FieldValue> values) {
  if (m_deck->cards.at(card).file != 0)
    throw formats::InputError("DeckEditor: cannot change a card inside an INCLUDE file (" +
                                std::string(m_deck->cards[card].name) + ")");
  m_deck->set_values(card, std::move(values));
}

std::int64_t DeckEditor::add_grid(const Eigen::Vector3d& x, std::int64_t cd, const std::string& ps) {
  formats::Grid g;
  g.id = new_grid_id();
  g.x = {x(0), x(1), x(2)};
  g.cd = cd;
  g.cd_blank = cd == 0;
  g.ps = ps;
  g.ps_blank = ps.empty();
  append(formats::write_grid(g));
  return g.id;
}

std::int64_t DeckEditor::add_desvar(const NewParameter& p, double xinit) {
  formats::Desvar d;
  d.id = new_desvar_id();
  d.label = p.label;
  d.xinit = xinit;
  d.xlb = p.lower;
  d.xub = p.upper;
  append(formats::write_desvar(d));
  parameters.push_back(p);
  return d.id;
}

void DeckEditor::add_dvprel1(const std::string& type, std::int64_t id, const std::string& pname, std::int64_t dvid,
                             double coef, double c0, std::optional<double> pmin) {
  formats::Dvprel1 r;
  r.id = new_relation_id();
  r.type = type;
  r.pid = id;
  r.pname = pname;
  r.pmin = pmin;
  r.c0 = c0;
  r.terms = {{dvid, coef}};
  append(formats::write_dvprel1(r));
}

std::string DeckEditor::text() const {
  std::string main = formats::render_file(*m_deck, 0);
  // Insert before the ENDDATA line (or at the end).
  std::size_t at = std::string::npos;
  for (std::size_t pos = 0; pos < main.size();) {
    std::size_t end = main.find('\n', pos);
    if (end == std::string::npos) end = main.size();
    std::size_t b = pos;
    while (b < end && (main[b] == ' ' || main[b] == '\t')) ++b;
    std::string word;
    for (std::size_t k = b; k < end && k < b + 7; ++k) word += static_cast<char>(std::toupper(static_cast<unsigned char>(main[k])));
    if (word == "ENDDATA") at = pos;
    pos = end + 1;
  }
  if (at == std::string::npos) {
    if (!main.empty() && main.back() != '\n') main += "\n";
    return main + m_appended;
  }
  return main.substr(0, at) + m_appended + main.substr(at);
}

double total_mass(const FeModel& model) {
  const auto ops = model.operators(model.initial_parameters(), false);
  const auto& gset = model.geometry().gset();
  Eigen::VectorXd e = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(gset.size()));
  for (const auto& g : model.geometry().grids()) e(static_cast<Eigen::Index>(g.dofs[0])) = 1.0;
  return e.dot(ops.Mg * e);
}

std::vector<std::unique_ptr<ModelExtension>> standard_extensions(const ExtensionOptions& options) {
  std::vector<std::unique_ptr<ModelExtension>> v;
  v.push_back(make_local_stiffness(options));
  v.push_back(make_missing_mass(options));
  v.push_back(make_support_dynamics(options));
  v.push_back(make_joint_flexibility(options));
  v.push_back(make_local_modes(options));
  return v;
}

}  // namespace ssid::estimator::diagnosis::hypotheses
