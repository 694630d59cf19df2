#include "estimator/deck_loading.hpp"

#include <stdexcept>

#include "formats/parse_error.hpp"

namespace ssid::estimator {

formats::BulkModel resolved_bulk(const formats::Deck& deck, const std::string& who,
                                 std::vector<std::string>* warnings) {
  formats::BulkModel model = formats::parse_bulk(deck);
  formats::resolve(deck, model);
  constexpr std::size_t kShown = 20;
  std::string errors;
  std::size_t count = 0;
  const std::vector<formats::Problem>* lists[] = {&deck.problems, &model.problems};
  for (const auto* list : lists)
    for (const auto& p : *list) {
      if (p.severity != formats::Problem::Severity::Error) {
        if (warnings) warnings->push_back(p.str());
      } else if (++count <= kShown) {
        errors += "\n  " + p.str();
      }
    }
  if (count)
    throw formats::InputError((who.empty() ? "" : who + ": ") + std::to_string(count) +
                                " error(s) in the deck; nothing assembled:" + errors +
                                (count > kShown ? "\n  ... and " + std::to_string(count - kShown) + " more" : ""));
  return model;
}

}  // namespace ssid::estimator
