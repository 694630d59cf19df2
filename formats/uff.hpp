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
///  | 58, 58b | function at a nodal DOF (FRF, time)  | Function58         |
///  | 1858    | qualifiers of the 58 that follows    | Qualifiers1858     |
///  | 2414    | analysis results at nodes (modes)    | NodalData55 (+2414)|
///  | 2412    | elements (test geometry lines)       | ElementSet2412     |
///  | 82      | trace lines (test geometry)          | TraceLine82        |
///  | 18      | coordinate systems (by points)       | CoordinateSystems18|
///  | 2420    | coordinate systems (by matrices)     | CoordinateSystems2420|
///  | other   | skipped, counted, kept verbatim      | UnknownDataset     |
///
/// Reading accepts what test-lab software writes: values that touch (fixed
/// columns are honoured, so `-1.23456E+00-2.34567E+00` is two fields), Fortran
/// `D` exponents, lower case, blank integer fields (Fortran reads them as 0),
/// CR-LF line ends, trailing blanks after delimiters, a byte-order mark before the
/// first delimiter and a DOS end-of-file mark after the last. A numeric line that does
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
/// The records of dataset 2414 (analysis data) that dataset 55 has no place for.
/// 2414 at nodes (dataset location 1) is read into NodalData55 — R9 and R14/R15
/// have 55's layout — so every consumer of 55 modes reads 2414 modes too:
///   R1 I10 analysis dataset label; R2 80A1 analysis dataset name;
///   R3 I10 dataset location (1 data at nodes; 2 on elements, 3 at nodes on
///      elements and 5 at points are kept verbatim, not read);
///   R4-R8 80A1 ID lines 1-5; R9 6I10 as 55's R6 (the fifth field "data type":
///      2 real, 4 real double, 5 complex, 6 complex double);
///   R10 8I10 design set, iteration, solution set, boundary condition, load set,
///      mode number, time step number, frequency number;
///   R11 2I10 creation option, number retained;
///   R12 6E13.5 time, frequency (Hz), eigenvalue, modal mass, viscous damping
///      ratio, hysteretic damping ratio;
///   R13 6E13.5 Re λ, Im λ, Re A (modal A or mass), Im A, Re B, Im B;
///   R14 I10 node; R15 NDV values (pairs when complex), 6 to a line (E13.5) or
///      3 to a line (D25.16, double precision).
/// On reading, NodalData55's int_params/real_params are set as a 55 of the same
/// analysis type would carry them (normal mode: [load set, mode], [frequency,
/// modal mass, viscous, hysteretic]; complex mode: [load set, mode], R13;
/// frequency response: [load set, frequency number], [frequency]; transient:
/// [load set, time step], [time]); the writer writes R10-R13 from this struct.
struct Analysis2414 {
  std::int64_t label = 1;
  std::string name = "NONE";
  int location = 1;
  std::array<std::int64_t, 8> r10{};
  std::array<std::int64_t, 2> r11{};
  std::array<double, 6> r12{};
  std::array<double, 6> r13{};
};

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
  std::optional<Analysis2414> analysis2414;  ///< set when read from (and written as) dataset 2414
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
  /// Binary 58b: record 12 is raw values, not text. The header line is
  /// (I6,1A1,I6,I6,I12,I12,I6,I6,I12,I12): 58, 'b', byte order (1 little endian,
  /// 2 big endian), floating-point format (2 IEEE 754; 1 DEC VMS and 3 IBM 370 are
  /// refused), number of ASCII lines (11), number of bytes, then four zeros. The
  /// values follow the ASCII record order (x, re, im as the ordinate type and
  /// spacing say), every one of them 4 bytes (ordinate types 2, 5) or 8 bytes
  /// (4, 6) — the abscissa of uneven data too, as Test.Lab and pyuff write it.
  bool binary = false;
  int byte_order = 1;  ///< 58b: 1 little endian, 2 big endian
  SourceLocation where;

  bool is_complex() const { return ordinate_type == 5 || ordinate_type == 6; }
  bool is_double() const { return ordinate_type == 4 || ordinate_type == 6; }
  /// The abscissa of every value: `x` when held (the reader fills it), else
  /// min + k · increment (a record built in memory as even data).
  std::vector<double> abscissa() const {
    if (!x.empty()) return x;
    std::vector<double> out;
    for (std::size_t k = 0; k < y.size(); ++k) out.push_back(abscissa_min + static_cast<double>(k) * abscissa_increment);
    return out;
  }
};

/// Dataset 1858: qualifiers of the dataset 58 that follows it (as Test.Lab writes them).
///   R1 (6I12) set record number, octave format (0 none, 1 1/1, 3 1/3, ...), measurement run, 3 unused;
///   R2 (12I6) weighting (0 none, 1 A, 2 B, 3 C, 4 D), window (0 none, 1 Hanning narrow, 2 Hanning
///      broad, 3 flattop, 4 exponential, 5 impact, 6 impact and exponential), amplitude units
///      (0 unknown, 1 half-peak, 2 peak, 3 RMS), normalization (0 unknown, 1 units squared,
///      2 units squared per Hz, 3 units squared seconds per Hz), abscissa, ordinate numerator,
///      ordinate denominator, z-axis data type qualifiers (0 translation, 1 rotation,
///      2 translation squared, 3 rotation squared), sampling type (0 dynamic, 1 static,
///      2 RPM from tach, 3 frequency from tach), 3 unused;
///   R3 (1P5E15.7) z RPM, z time, z order, number of samples, unused;
///   R4 (1P5E15.7) user values 1-4, exponential window damping factor;
///   R5 (1P5E15.7) unused; R6 (2A2,2X,2A2) response and reference direction; R7 (40A2) unused.
struct Qualifiers1858 {
  std::array<std::int64_t, 6> r1{};
  std::array<std::int64_t, 12> r2{};
  std::array<double, 15> reals{};  ///< R3-R5
  std::string directions = "NONE";  ///< R6 as read (right-trimmed)
  std::string r7 = "NONE";
  SourceLocation where;
  int window() const { return static_cast<int>(r2[1]); }
  double samples() const { return reals[3]; }
  double exponential_damping() const { return reals[9]; }
};

/// One element of dataset 2412: R1 (6I10) label, FE descriptor id, physical and
/// material property tables, color, number of nodes; beams (descriptors 11, 21,
/// 22, 23, 24) then R2 (3I10) orientation node, fore-end and aft-end cross sections;
/// then the node labels (8I10, continued).
struct Element2412 {
  std::int64_t id = 0;
  int descriptor = 0;
  std::int64_t physical = 0, material = 0;
  int color = 0;
  std::optional<std::array<std::int64_t, 3>> beam;  ///< orientation node, fore, aft (beams only)
  std::vector<std::int64_t> nodes;
  static bool is_beam_descriptor(int d) { return d == 11 || d == 21 || d == 22 || d == 23 || d == 24; }
};

/// Dataset 2412: elements (for a test, the lines and faces drawn between its nodes).
struct ElementSet2412 {
  std::vector<Element2412> elements;
  SourceLocation where;
};

/// Dataset 82: a trace line of the test geometry.
///   R1 (3I10) trace line number, number of nodes, color; R2 (80A1) label;
///   R3 (8I10) the nodes, continued 8 to a line; a 0 lifts the pen (the next node starts a new line).
struct TraceLine82 {
  std::int64_t id = 0;
  int color = 0;
  std::string label = "NONE";
  std::vector<std::int64_t> nodes;
  SourceLocation where;
};

/// A coordinate system as ssid applies it: global = origin + Σ_i local_i · axes.row(i)
/// for a Cartesian one (rows: the local unit axes in global components); a
/// cylindrical one takes (r, θ in degrees, z) and a spherical one (r, θ, φ in
/// degrees: θ from local z, φ about it from local x) to local Cartesian first.
struct CoordinateSystem {
  std::int64_t id = 0;
  int type = 0;  ///< 0 Cartesian, 1 cylindrical, 2 spherical
  std::array<std::array<double, 3>, 3> axes{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  std::array<double, 3> origin{0, 0, 0};
  std::string name;

  /// A point given in this system, in global coordinates.
  std::array<double, 3> to_global(const std::array<double, 3>& local) const;
  /// The global unit vector of local direction 1..3 (X, Y, Z; for cylindrical
  /// R, θ, Z and spherical R, θ, φ the local basis at the point `local`).
  std::array<double, 3> axis_at(int direction, const std::array<double, 3>& local) const;
};

/// Dataset 18: coordinate systems defined by three points in a reference system.
///   R1 (5I10) number, type (0 Cartesian, 1 cylindrical, 2 spherical), reference system,
///      color, method of definition (1: origin, point on +X, point in the +XZ plane);
///   R2 (40A2) name; R3 (1P6E13.5) origin, point on +X; R4 (1P3E13.5) point in +XZ.
///   R1-R4 repeated per system.
struct Cs18 {
  std::int64_t id = 0;
  int type = 0;
  std::int64_t reference = 0;
  int color = 0;
  int method = 1;
  std::string name = "NONE";
  std::array<double, 3> origin{}, x_point{}, xz_point{};
};
struct CoordinateSystems18 {
  std::vector<Cs18> systems;
  SourceLocation where;
};

/// Dataset 2420: coordinate systems of a part.
///   R1 (I10) part UID; R2 (40A2) part name; R3 (3I10) label, type (0 Cartesian,
///   1 cylindrical, 2 spherical), color; R4 (40A2) name; R5-R7 (1P3D25.16) the
///   transformation matrix rows; R8 (1P3D25.16) the origin. R3-R8 repeated.
/// The matrix rows are taken as the local axes in global components (the I-DEAS
/// convention: global = origin + local · T).
struct Cs2420 {
  std::int64_t id = 0;
  int type = 0;
  int color = 0;
  std::string name = "NONE";
  std::array<std::array<double, 3>, 3> rows{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  std::array<double, 3> origin{};
};
struct CoordinateSystems2420 {
  std::int64_t part_uid = 1;
  std::string part_name = "NONE";
  std::vector<Cs2420> systems;
  SourceLocation where;
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

using Dataset = std::variant<Header151, Units164, NodeSet, NodalData55, Function58, Qualifiers1858, ElementSet2412,
                             TraceLine82, CoordinateSystems18, CoordinateSystems2420, UnknownDataset>;

/// Dataset number of a dataset.
int dataset_number(const Dataset& d);

/// A universal file: its datasets in file order.
struct UffFile {
  std::string path;
  std::vector<Dataset> datasets;

  /// All nodes of the 15 and 2411 datasets, in file order.
  std::vector<Node> nodes() const;
  /// All nodes with positions in the global system: each node's definition
  /// system (datasets 18, 2420) applied. Throws InputError naming the node when
  /// it refers to a system the file does not define.
  std::vector<Node> nodes_in_global() const;
  /// The coordinate systems of the 18 and 2420 datasets by id, resolved to global
  /// (18's reference systems applied). Throws InputError for a reference to an
  /// undefined system, a reference cycle, or three points that span no plane.
  std::map<std::int64_t, CoordinateSystem> coordinate_systems() const;
  /// The global unit vector of measurement direction ±1..±3 at `node` (its
  /// displacement system applied; rotations ±4..±6 about the same axes). Zero
  /// vector for direction 0 (scalar).
  std::array<double, 3> direction_in_global(const Node& node, int direction) const;
  /// The 55 and 2414 datasets at nodes, in file order (pointers into `datasets`).
  std::vector<const NodalData55*> nodal_data() const;
  /// The 58 and 58b datasets, in file order.
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
/// Extended writes 55, 2414 and 15 values and the ASCII data of single-precision
/// 58 (ordinate types 2, 5) as 1P E25.16 (three per line), which
/// ssid and free-format readers read back to the last bit; use it for
/// synthetic data that must survive a round trip exactly.
enum class Precision { Standard, Extended };

/// The universal-file text of `file` (datasets in order).
std::string format_uff(const UffFile& file, Precision precision = Precision::Standard);
/// Writes `file` to `path`; throws std::runtime_error when the file cannot be written.
void write_uff(const UffFile& file, const std::string& path, Precision precision = Precision::Standard);

}  // namespace ssid::formats::uff
