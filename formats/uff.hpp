#pragma once
/// \file uff.hpp
/// Universal files (UFF/UNV, the SDRC I-DEAS exchange format that test-lab
/// software writes): plain data for the datasets ssid uses, a reader and a writer.
///
/// A universal file is a sequence of datasets, each framed by delimiter lines
/// holding `-1` in columns 1-6 (`    -1`); the line after the opening delimiter
/// holds the dataset number in columns 1-6 (I6). Records are fixed-column
/// Fortran lines (I10, E13.5, D25.16, 80A1 ...). Supported here:
///
///  | dataset | content                              | kept as            |
///  |---------|--------------------------------------|--------------------|
///  | 151     | header (model, program, dates)       | Header151 (lines)  |
///  | 164     | units (code, factors to SI)          | Units164           |
///  | 15      | nodes, single precision              | NodeSet            |
///  | 2411    | nodes, double precision              | NodeSet            |
///  | 55      | data at nodes (modes, FRF at a step) | NodalData55        |
///  | 58      | function at a nodal DOF (FRF, time)  | Function58 (ASCII) |
///  | other   | skipped, counted, kept verbatim      | UnknownDataset     |
///
/// Reading accepts what test-lab software writes: values that touch (fixed
/// columns are honoured, so `-1.23456E+00-2.34567E+00` is two fields), Fortran
/// `D` exponents, lower case, blank integer fields (Fortran reads them as 0),
/// CR-LF line ends, trailing blanks after delimiters. A numeric line that does
/// not fit its fixed columns but holds the expected number of blank-separated
/// values is read in free format (Fortran list-directed style), since several
/// writers widen fields. Every error names file, line, dataset, record, field
/// and what was expected.
#include <array>
#include <complex>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "formats/parse_error.hpp"

namespace ssid::formats::uff {

/// Dataset 151: header. Records 1-7 kept verbatim (right-trimmed) so they are
/// written back unchanged; the named accessors read them.
///   R1 80A1 model file name; R2 80A1 description; R3 80A1 program that created
///   the database; R4 (10A1,10A1,3I10) date/time created, versions, file type;
///   R5 (10A1,10A1) date/time saved; R6 80A1 program that wrote the file;
///   R7 (10A1,10A1) date/time written.
struct Header151 {
  std::vector<std::string> lines;  ///< the records as read (7 expected)
  SourceLocation where;
  std::string model_name() const { return lines.size() > 0 ? lines[0] : ""; }
  std::string description() const { return lines.size() > 1 ? lines[1] : ""; }
  std::string program() const { return lines.size() > 5 ? lines[5] : ""; }
};

/// Dataset 164: units.
///   R1 (I10,20A1,I10) units code, description, temperature mode (1 absolute, 2 relative);
///   R2 (3D25.17) length, force, temperature factors; R3 (D25.17) temperature offset.
/// The factors convert SI to file units: a value in file units divided by the
/// factor is in SI.
struct Units164 {
  int code = 1;                ///< 1 SI, 2 BG, 3 MG, ... 9 user defined
  std::string description;
  int temperature_mode = 2;
  double length = 1, force = 1, temperature = 1, temperature_offset = 0;
  SourceLocation where;
};

/// One test node (datasets 15 and 2411).
struct Node {
  std::int64_t id = 0;
  int definition_cs = 0;    ///< coordinate system of the position (0 = global)
  int displacement_cs = 0;  ///< system in which the node's measured directions are given (0 = global)
  int color = 0;
  std::array<double, 3> xyz{0, 0, 0};
};

/// Dataset 15 (single precision, one line per node:
///   R1 (4I10,1P3E13.5) label, definition CS, displacement CS, color, X, Y, Z)
/// or dataset 2411 (double precision, two lines per node:
///   R1 (4I10) label, export CS, displacement CS, color;  R2 (1P3D25.16) X, Y, Z).
struct NodeSet {
  int dataset = 2411;  ///< 15 or 2411: the layout to write back
  std::vector<Node> nodes;
  SourceLocation where;
};

/// Dataset 55: data at nodes (mode shapes, or a response at one frequency).
///   R1-R5 80A1 ID lines;
///   R6 (6I10) model type, analysis type, data characteristic, specific data type,
///      data type (2 real, 5 complex), values per node NDV;
///   R7 (8I10) NINT, NREAL, then NINT type-specific integers;
///   R8 (6E13.5) NREAL type-specific reals;
///   R9 (I10) node number;  R10 (6E13.5) NDV values (NDV complex pairs when complex);
///   R9-R10 repeated per node.
/// Type-specific parameters (R7 fields 3.., R8):
///   analysis 2 normal mode: [load case, mode no.], [frequency Hz, modal mass,
///     viscous damping ratio, hysteretic damping ratio];
///   analysis 3/7 complex eigenvalue: [load case, mode no.], [Re λ, Im λ, Re A, Im A, Re B, Im B];
///   analysis 5 frequency response: [load case, frequency step], [frequency Hz];
///   analysis 1 static: [load case], [0]; analysis 4 transient: [load case, step], [time s].
struct NodalData55 {
  std::array<std::string, 5> id_lines;
  int model_type = 1;
  int analysis_type = 2;
  int data_characteristic = 2;  ///< 1 scalar, 2 3-DOF translation, 3 6-DOF translation+rotation
  int specific_data_type = 8;   ///< 8 displacement, 11 velocity, 12 acceleration, ...
  int data_type = 2;            ///< 2 real, 5 complex (single precision in the file)
  int values_per_node = 3;      ///< NDV
  std::vector<std::int64_t> int_params;  ///< R7 fields 3.. (NINT values)
  std::vector<double> real_params;       ///< R8 (NREAL values)
  std::vector<std::int64_t> nodes;       ///< R9 per node
  Eigen::MatrixXd values;                ///< nodes x NDV (real data)
  Eigen::MatrixXcd complex_values;       ///< nodes x NDV (complex data)
  SourceLocation where;

  bool is_complex() const { return data_type == 5 || data_type == 6; }
  bool is_normal_mode() const { return analysis_type == 2; }
  bool is_complex_mode() const { return analysis_type == 3 || analysis_type == 7; }
  /// Mode number (normal and complex modes), frequency step, ...: R7 field 4.
  std::int64_t mode_number() const { return int_params.size() > 1 ? int_params[1] : 0; }
  std::int64_t load_case() const { return int_params.empty() ? 0 : int_params[0]; }
  /// Normal modes and frequency response: R8 field 1 (Hz). Complex modes: the
  /// damped natural frequency |λ|/2π.
  double frequency_hz() const;
  double modal_mass() const { return is_normal_mode() && real_params.size() > 1 ? real_params[1] : 0.0; }
  double viscous_damping() const { return is_normal_mode() && real_params.size() > 2 ? real_params[2] : 0.0; }
  double hysteretic_damping() const { return is_normal_mode() && real_params.size() > 3 ? real_params[3] : 0.0; }
  /// Complex modes: eigenvalue λ = σ + iω (rad/s); damping ratio −σ/|λ|.
  std::complex<double> eigenvalue() const;

  /// Builds a real normal-mode dataset (analysis type 2, data type 2) with the
  /// standard parameters; NDV = values.cols() (3 or 6).
  static NodalData55 normal_mode(std::int64_t mode, double frequency_hz, std::vector<std::int64_t> nodes,
                                 Eigen::MatrixXd values, double modal_mass = 0, double viscous_damping = 0);
};

/// Axis description of dataset 58, records 8-11: (I10,3I5,2(1X,20A1)).
struct Axis58 {
  int specific_data_type = 0;  ///< 0 unknown, 1 general, 8 displacement, 12 acceleration, 13 excitation force, 18 time, 19 frequency...
  int length_exponent = 0, force_exponent = 0, temperature_exponent = 0;
  std::string label = "NONE", units = "NONE";
};

/// Dataset 58: function at a nodal DOF (FRF, coherence, time history, ...), ASCII.
///   R1-R5 80A1 ID lines;
///   R6 (2(I5,I10),2(1X,10A1,I10,I4)) function type, function id, version, load case,
///      response entity, response node, response direction, reference entity,
///      reference node, reference direction (directions ±1..±6 = ±X,Y,Z,RX,RY,RZ; 0 scalar);
///   R7 (3I10,3E13.5) ordinate type (2 real, 4 real double, 5 complex, 6 complex double),
///      number of points, spacing (0 uneven, 1 even), abscissa minimum, increment, z value;
///   R8-R11 Axis58 for abscissa, ordinate numerator, ordinate denominator, z axis;
///   R12 data:  type 2/5: 6E13.5 per line (x,y pairs or x,re,im triples when uneven);
///              type 4 even: 4E20.12; uneven: 2(E13.5,E20.12);
///              type 6 even: 4E20.12 (re,im); uneven: E13.5,2E20.12 (x,re,im).
struct Function58 {
  std::array<std::string, 5> id_lines;
  int function_type = 4;  ///< 1 time response, 2 auto spectrum, 3 cross spectrum, 4 FRF, 6 coherence, ...
  std::int64_t function_id = 0;
  int version = 0;
  std::int64_t load_case = 0;
  std::string response_entity = "NONE";
  std::int64_t response_node = 0;
  int response_direction = 0;
  std::string reference_entity = "NONE";
  std::int64_t reference_node = 0;
  int reference_direction = 0;
  int ordinate_type = 6;
  bool even = true;
  double abscissa_min = 0, abscissa_increment = 0, z_value = 0;
  std::array<Axis58, 4> axes;  ///< abscissa, ordinate numerator, ordinate denominator, z
  std::vector<double> x;       ///< abscissa (computed from min/increment when even)
  std::vector<std::complex<double>> y;  ///< ordinate (imaginary part 0 for real data)
  SourceLocation where;

  bool is_complex() const { return ordinate_type == 5 || ordinate_type == 6; }
  bool is_double() const { return ordinate_type == 4 || ordinate_type == 6; }
};

/// A dataset ssid does not interpret (or a binary 58b): the lines between the
/// dataset-number line and the closing delimiter, kept verbatim so a written file
/// carries it unchanged.
struct UnknownDataset {
  int number = 0;
  std::string header_line;  ///< the dataset-number line as read (may carry binary-format fields)
  std::string body;         ///< raw bytes between the number line and the closing delimiter
  SourceLocation where;
};

using Dataset = std::variant<Header151, Units164, NodeSet, NodalData55, Function58, UnknownDataset>;

/// Dataset number of a dataset.
int dataset_number(const Dataset& d);

/// A universal file: its datasets in file order.
struct UffFile {
  std::string path;
  std::vector<Dataset> datasets;

  /// All nodes of the 15 and 2411 datasets, in file order.
  std::vector<Node> nodes() const;
  /// The 55 datasets, in file order (pointers into `datasets`).
  std::vector<const NodalData55*> nodal_data() const;
  /// The 58 datasets, in file order.
  std::vector<const Function58*> functions() const;
  /// Count per dataset number of the datasets kept verbatim (skipped).
  std::map<int, std::size_t> skipped() const;
};

/// Reads a universal file; throws ParseError (file:line: dataset N record R
/// field F (name): expected ..., got "...") on bad input.
UffFile read_uff(const std::string& path);
/// Parses universal-file text; `name` is used in messages.
UffFile parse_uff(const std::string& text, const std::string& name);

/// How values are written. Standard follows the dataset definitions exactly
/// (1P E13.5 for 15/55, D25.16 for 2411, E20.12 for double 58 data).
/// Extended writes 55 and 15 values as 1P E25.16 (three per line), which
/// ssid and free-format readers read back to the last bit; use it for
/// synthetic data that must survive a round trip exactly.
enum class Precision { Standard, Extended };

/// The universal-file text of `file` (datasets in order).
std::string format_uff(const UffFile& file, Precision precision = Precision::Standard);
/// Writes `file` to `path`; throws std::runtime_error when the file cannot be written.
void write_uff(const UffFile& file, const std::string& path, Precision precision = Precision::Standard);

}  // namespace ssid::formats::uff
