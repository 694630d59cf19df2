/// \file matrix_json.cpp
#include "cli/matrix_json.hpp"

#include <fstream>
#include <iostream>
#include <stdexcept>

#include "formats/parse_error.hpp"

namespace ssid::cli {

namespace {

template <class T>
nlohmann::json make(const std::string& name, int form, const std::string& form_name, int precision,
                    const Eigen::SparseMatrix<T>& a) {
  nlohmann::json j;
  j["name"] = name;
  j["rows"] = a.rows();
  j["cols"] = a.cols();
  j["form"] = form;
  j["form_name"] = form_name;
  j["precision"] = precision;
  j["precision_name"] = precision_name(precision);
  nlohmann::json e = nlohmann::json::array();
  for (Eigen::Index c = 0; c < a.outerSize(); ++c)
    for (typename Eigen::SparseMatrix<T>::InnerIterator it(a, c); it; ++it)
      e.push_back({it.row() + 1, c + 1, std::real(it.value()), std::imag(it.value())});
  j["entries"] = std::move(e);
  return j;
}

}  // namespace

std::string precision_name(int p) {
  switch (p) {
    case 1: return "real single";
    case 2: return "real double";
    case 3: return "complex single";
    case 4: return "complex double";
    default: return "precision " + std::to_string(p);
  }
}

nlohmann::json matrix_json(const std::string& name, int form, const std::string& form_name, int precision,
                           const Eigen::SparseMatrix<std::complex<double>>& values) {
  return make(name, form, form_name, precision, values);
}
nlohmann::json matrix_json(const std::string& name, int form, const std::string& form_name, int precision,
                           const Eigen::SparseMatrix<double>& values) {
  return make(name, form, form_name, precision, values);
}

nlohmann::json matrix_json(const formats::Op4Matrix& m) {
  nlohmann::json j = m.is_complex()
                         ? make(m.name, m.form, formats::op4_form::name(m.form), static_cast<int>(m.precision), m.complex)
                         : make(m.name, m.form, formats::op4_form::name(m.form), static_cast<int>(m.precision), m.real);
  return j;
}

namespace {

void object_text(const nlohmann::json& o, const std::string& indent, std::string& out) {
  out += "{";
  bool first = true;
  for (auto it = o.begin(); it != o.end(); ++it) {
    out += first ? "\n" : ",\n";
    first = false;
    out += indent + "  " + nlohmann::json(it.key()).dump() + ": ";
    if (it.key() == "entries" && it->is_array()) {
      if (it->empty()) {
        out += "[]";
        continue;
      }
      out += "[";
      bool f2 = true;
      for (const auto& e : *it) {
        out += f2 ? "\n" : ",\n";
        f2 = false;
        out += indent + "    " + e.dump();
      }
      out += "\n" + indent + "  ]";
    } else {
      out += it->dump();
    }
  }
  out += first ? "}" : "\n" + indent + "}";
}

}  // namespace

std::string matrix_json_text(const nlohmann::json& j) {
  std::string out;
  if (j.is_array()) {
    out += "[";
    bool first = true;
    for (const auto& o : j) {
      out += first ? "\n  " : ",\n  ";
      first = false;
      object_text(o, "  ", out);
    }
    out += first ? "]" : "\n]";
  } else {
    object_text(j, "", out);
  }
  return out + "\n";
}

void write_matrix_json(const std::string& path, const nlohmann::json& j) {
  const std::string text = matrix_json_text(j);
  if (path == "-") {
    std::cout << text;
    return;
  }
  std::ofstream o(path, std::ios::binary);
  if (!o) throw formats::InputError("cannot write " + path);
  o << text;
  if (!o) throw formats::InputError("error writing " + path);
}

}  // namespace ssid::cli
