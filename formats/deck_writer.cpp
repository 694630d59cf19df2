#include "formats/deck_writer.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "formats/nastran_number.hpp"
#include "formats/parse_error.hpp"

namespace ssid::formats {

namespace fs = std::filesystem;

namespace {

/// Text of `v` in at most `width` characters written exactly; false when impossible.
bool exact_text(const FieldValue& v, int width, std::string& out) {
  if (std::holds_alternative<std::monostate>(v)) { out.clear(); return true; }
  if (auto* i = std::get_if<std::int64_t>(&v)) { out = std::to_string(*i); return static_cast<int>(out.size()) <= width; }
  if (auto* d = std::get_if<double>(&v)) {
    auto s = format_real_exact(*d, width);
    if (!s) return false;
    out = *s;
    return true;
  }
  out = std::get<std::string>(v);
  return static_cast<int>(out.size()) <= width;
}

/// Does the original field text already spell value `v`?
bool same_value(std::string_view text, const FieldValue& v) {
  if (std::holds_alternative<std::monostate>(v)) return text.empty();
  if (auto* i = std::get_if<std::int64_t>(&v)) { auto p = parse_integer(text); return p && *p == *i; }
  if (auto* d = std::get_if<double>(&v)) { auto p = parse_real(text); return p && *p == *d; }
  return text == std::get<std::string>(v);
}

std::string pad(const std::string& s, std::size_t w) {
  return s.size() >= w ? s : s + std::string(w - s.size(), ' ');
}

void rtrim(std::string& s) {
  while (!s.empty() && s.back() == ' ') s.pop_back();
}

}  // namespace

std::string format_card(const std::string& name, const std::vector<FieldValue>& values, FieldFormat format,
                        const std::string& newline, const Card* original) {
  const std::size_t n = values.size();
  std::vector<std::string> text(n);
  bool large = format == FieldFormat::Large;
  auto fill = [&](int width) {
    bool ok = true;
    for (std::size_t i = 1; i < n; ++i) {
      if (original && i < original->original_fields.size() && same_value(original->original_fields[i], values[i]) &&
          static_cast<int>(original->original_fields[i].size()) <= width) {
        text[i] = std::string(original->original_fields[i]);
        continue;
      }
      if (!exact_text(values[i], width, text[i])) {
        if (width == 16 && std::holds_alternative<double>(values[i])) {
          text[i] = format_real_rounded(std::get<double>(values[i]), 16);
        } else if (width == 16) {
          throw InputError(name + " field " + std::to_string(i + 1) + ": value '" + text[i] +
                                      "' does not fit in 16 characters");
        } else {
          ok = false;
        }
      }
    }
    return ok;
  };
  if (!large && !fill(8)) large = true;
  if (large) fill(16);
  std::size_t last = n;
  while (last > 1 && text[last - 1].empty()) --last;

  std::string out;
  const bool free = format == FieldFormat::Free;
  const std::size_t per_line = large ? 4 : 8;
  std::size_t i = 1;
  bool first = true;
  do {
    std::string line;
    if (free) {
      line = first ? (large ? name + "*" : name) : (large ? "*" : "+");
      std::size_t stop = std::min(last, i + per_line);
      for (std::size_t k = i; k < stop; ++k) line += "," + text[k];
    } else {
      line = pad(first ? (large ? name + "*" : name) : (large ? "*" : "+"), 8);
      for (std::size_t k = i; k < std::min(last, i + per_line); ++k) line += pad(text[k], large ? 16 : 8);
      rtrim(line);
    }
    out += line + newline;
    i += per_line;
    first = false;
  } while (i < last);
  return out;
}

std::string render_file(const Deck& deck, std::size_t file) {
  const SourceFile& f = deck.files.at(file);
  // A replicated card ("=" and "=(n)" lines, deck_reader.cpp) is derived from the card
  // before it: when one card of a chain changed, every card of the chain is written
  // out in full, so the cards after the change keep their values.
  std::vector<std::int32_t> changed_chains;
  for (const Chunk& c : f.chunks) {
    if (c.kind != Chunk::Kind::Card) continue;
    const Card& card = deck.cards[c.index];
    if (card.modified && card.replication_root >= 0) changed_chains.push_back(card.replication_root);
  }
  // A card of a changed chain is written in full; so is a changed card.
  auto in_changed_chain = [&](const Card& card) {
    return card.replication_root >= 0 &&
           std::find(changed_chains.begin(), changed_chains.end(), card.replication_root) != changed_chains.end();
  };
  std::string out;
  out.reserve(f.text.size() + 256);
  for (const Chunk& c : f.chunks) {
    // A continuation matched by marker belongs to a card written whole elsewhere.
    if (c.kind == Chunk::Kind::Detached && (deck.cards[c.index].modified || in_changed_chain(deck.cards[c.index])))
      continue;
    if (c.kind == Chunk::Kind::Card) {
      const Card& card = deck.cards[c.index];
      const bool whole = in_changed_chain(card);
      if (whole && !card.modified) {
        std::vector<FieldValue> values{card.name};
        for (std::size_t i = 1; i < card.size(); ++i)
          values.push_back(card.field(i).empty() ? FieldValue{} : FieldValue{std::string(card.field(i))});
        out += format_card(card.name, values, FieldFormat::Free, f.newline, nullptr);
        continue;
      }
      if (card.modified) {
        const bool keep_text = card.end > card.begin && !whole;
        out += format_card(card.name, card.values, whole ? FieldFormat::Free : card.format, f.newline,
                           keep_text ? &card : nullptr);
        continue;
      }
    }
    out.append(f.text, c.begin, c.end - c.begin);
  }
  return out;
}

namespace {
bool file_has_changes(const Deck& deck, std::size_t file) {
  for (const Chunk& c : deck.files[file].chunks)
    if (c.kind == Chunk::Kind::Card && deck.cards[c.index].modified) return true;
  return false;
}

void write_one(const Deck& deck, std::size_t file, const fs::path& out, std::vector<std::string>& written) {
  std::error_code ec;
  for (const SourceFile& src : deck.files) {
    if (src.path.empty()) continue;
    if (fs::exists(src.path, ec) && fs::exists(out, ec) && fs::equivalent(src.path, out, ec))
      throw InputError("refusing to overwrite input file " + src.path + " (choose another output path)");
  }
  if (out.has_parent_path()) fs::create_directories(out.parent_path(), ec);
  std::ofstream o(out, std::ios::binary);
  if (!o) throw InputError("cannot write " + out.string());
  const std::string text = render_file(deck, file);
  o.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!o) throw InputError("error writing " + out.string());
  written.push_back(out.string());
  for (const Chunk& c : deck.files[file].chunks) {
    if (c.kind != Chunk::Kind::Include) continue;
    const SourceFile& child = deck.files[c.index];
    fs::path name(child.include_name);
    if (name.is_absolute()) {
      if (file_has_changes(deck, c.index))
        throw InputError("INCLUDE '" + child.include_name +
                                 "' has an absolute path and holds changed cards; it cannot be written beside " +
                                 out.string());
      continue;
    }
    write_one(deck, c.index, out.parent_path() / name, written);
  }
}
}  // namespace

std::vector<std::string> write_deck(const Deck& deck, const std::string& path) {
  std::vector<std::string> written;
  if (deck.files.empty()) throw std::runtime_error("write_deck: empty deck");
  write_one(deck, 0, fs::path(path), written);
  return written;
}

}  // namespace ssid::formats
