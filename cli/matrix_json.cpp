/// \file matrix_json.cpp
#include "cli/matrix_json.hpp"

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

}  // namespace ssid::cli
