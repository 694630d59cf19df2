#pragma once
/// \file uff_fields.hpp
/// Fixed-column typed field readers for universal files: the only place UFF
/// field errors are raised. Internal to the UFF reader.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "formats/parse_error.hpp"
#include "formats/text_util.hpp"

namespace ssid::formats::uff::detail {

/// One line of the file without its line end; `begin`/`end` are byte offsets of
/// the line start and of the character after its line end.
struct Line {
  std::string_view text;
  std::uint32_t number = 0;  ///< 1-based
  std::size_t begin = 0, end = 0;
};

/// Splits a buffer into lines on demand (LF or CR-LF), and can skip raw bytes
/// (binary dataset 58b).
class Scanner {
public:
  explicit Scanner(const std::string& text) : m_text(text) {}
  bool at_end() const { return m_pos >= m_text.size(); }
  Line next();
  /// Skips n bytes (counting the newlines among them so later line numbers stay right).
  void skip_bytes(std::size_t n);
  std::size_t offset() const { return m_pos; }
  std::uint32_t line_number() const { return m_line; }

private:
  const std::string& m_text;
  std::size_t m_pos = 0;
  std::uint32_t m_line = 0;
};

/// True for a dataset delimiter: `-1` right-justified in columns 1-6, nothing else.
bool is_delimiter(std::string_view line);
/// True when the line holds only blanks.
bool is_blank(std::string_view line);
/// The line with trailing blanks (and CR) removed.
std::string rtrim(std::string_view s);
/// Position of the first byte of `line` that is not text (a control character
/// other than tab, CR and form feed, or DEL); nullopt for a text line. Bytes of
/// 0x80 and above pass: ID lines may hold Latin-1 or UTF-8.
std::optional<std::size_t> first_non_text(std::string_view line);
/// Quoted text and bytes in messages: one way for every reader (text_util.hpp).
using formats::detail::byte_hex;
using formats::detail::quoted;

/// The kind of one fixed-column field.
enum class Kind { Integer, IntegerOrBlank, Real, RealOrBlank, Text, Skip };

/// A field of a record: `width` columns, read as `kind`; `name` is used in messages.
struct FieldSpec {
  int width;
  Kind kind;
  const char* name;
};

/// A value read from a field.
struct Value {
  std::int64_t i = 0;
  double d = 0;
  std::string s;
};

/// Where a record is read: for messages "file:line: dataset D record R field F (name): ...".
struct RecordContext {
  const std::string* file = nullptr;
  int dataset = 0;
  int record = 0;
  std::uint32_t end_line = 0;  ///< line of the closing delimiter: where "ended early" is reported
  SourceLocation at(const Line& line) const { return SourceLocation{*file, line.number, {}}; }
  [[noreturn]] void fail(const Line& line, const std::string& message) const;
  [[noreturn]] void fail_field(const Line& line, int field, const char* name, const std::string& expected,
                               std::string_view got) const;
};

/// Reads the fields of one line in fixed columns. When a numeric field fails and
/// the record has no text fields, the line is read in free format instead if it
/// holds exactly as many blank-separated values as there are non-skip fields
/// (blank-or-default fields may then be missing at the end). When the trailing
/// reals sit in equal columns of another width (1P E25.16 where E13.5 is the
/// standard), they are read in those. Otherwise throws the error of the first
/// bad field, in the columns its values were laid out in.
std::vector<Value> read_fields(const RecordContext& ctx, const Line& line, const std::vector<FieldSpec>& specs,
                               int first_field_number = 1);

/// Reads the `count` reals of one record, which continue over lines, each line
/// laid out as `widths` (e.g. 6 x 13 for 6E13.5, {13, 20, 13, 20} for
/// 2(E13.5,E20.12)). The record's first line decides its layout: these columns;
/// equal columns of another width w (a writer that widened them), 80/w to a
/// line; or blank-separated values. In columns every line but the last is full,
/// so a line that ends early is reported at that line and field; blank-separated
/// values may stop at any line end but must then be continued by more of them.
/// `lines`/`pos` is the body being read; `pos` advances. `name` describes the
/// values for messages.
std::vector<double> read_real_stream(const RecordContext& ctx, const std::vector<Line>& lines, std::size_t& pos,
                                     std::size_t count, const std::vector<int>& widths, const char* name);

/// Same for integers (e.g. 8I10 continuation of dataset 55 record 7).
std::vector<std::int64_t> read_integer_stream(const RecordContext& ctx, const std::vector<Line>& lines,
                                              std::size_t& pos, std::size_t count, int per_line, int width,
                                              const char* name);

}  // namespace ssid::formats::uff::detail
