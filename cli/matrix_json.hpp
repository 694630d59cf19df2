#pragma once
/// \file matrix_json.hpp
/// The JSON layout of `ssid op4 dump` and `ssid dmig dump`:
/// {"name","rows","cols","form","precision","entries":[[row,col,re,im],...]},
/// rows and columns counted from 1 (as NASTRAN does), entries by column then row.
#include <complex>
#include <string>

#include <Eigen/SparseCore>
#include <nlohmann/json.hpp>

#include "formats/op4.hpp"

namespace ssid::cli {

/// `form` and `precision` are NASTRAN's codes (OP4 FORM/TYPE, DMIG IFO/TIN);
/// `form_name` is added for readers. Real matrices get im = 0.
nlohmann::json matrix_json(const std::string& name, int form, const std::string& form_name, int precision,
                           const Eigen::SparseMatrix<std::complex<double>>& values);
nlohmann::json matrix_json(const std::string& name, int form, const std::string& form_name, int precision,
                           const Eigen::SparseMatrix<double>& values);
/// An OP4 matrix in that layout (plus "storage").
nlohmann::json matrix_json(const formats::Op4Matrix& m);

/// JSON text of one matrix object or a list of them: two-space indentation with
/// each entry [row, col, re, im] on one line (large matrices stay readable).
std::string matrix_json_text(const nlohmann::json& j);
/// Writes matrix_json_text to a file; "-" writes to stdout.
void write_matrix_json(const std::string& path, const nlohmann::json& j);

/// "real single", "real double", "complex single", "complex double".
std::string precision_name(int precision);

}  // namespace ssid::cli
