// Probe kinds, fields and columns (core/probes.hpp).
#include "afemp/probes.hpp"

#include <cmath>

namespace afemp::core {

const char* to_string(ProbeKind k) {
  switch (k) {
    case ProbeKind::particle:
      return "particle";
    case ProbeKind::node:
      return "node";
    case ProbeKind::element:
      return "element";
    case ProbeKind::mean_velocity:
      return "mean_velocity";
    case ProbeKind::extreme:
      return "extreme";
    case ProbeKind::force:
      return "force";
  }
  return "?";
}

const char* to_string(ProbeField f) {
  switch (f) {
    case ProbeField::pressure:
      return "pressure";
    case ProbeField::von_mises:
      return "von_mises";
    case ProbeField::plastic_strain:
      return "plastic_strain";
    case ProbeField::speed:
      return "speed";
    case ProbeField::vx:
      return "vx";
    case ProbeField::vy:
      return "vy";
    case ProbeField::vz:
      return "vz";
    case ProbeField::x:
      return "x";
    case ProbeField::y:
      return "y";
    case ProbeField::z:
      return "z";
  }
  return "?";
}

std::vector<std::string> probe_columns(ProbeKind k) {
  switch (k) {
    case ProbeKind::particle:
    case ProbeKind::element:
      return {"x", "y", "z", "vx", "vy", "vz", "pressure", "von_mises", "plastic_strain"};
    case ProbeKind::node:
      return {"x", "y", "z", "vx", "vy", "vz"};
    case ProbeKind::mean_velocity:
      return {"vx", "vy", "vz"};
    case ProbeKind::extreme:
      return {"value", "x", "y", "z"};
    case ProbeKind::force:
      return {"fx", "fy", "fz", "normal", "tangential"};
  }
  return {};
}

int ProbeSeries::column(const std::string& column_name) const {
  for (std::size_t c = 0; c < columns.size(); ++c)
    if (columns[c] == column_name) return static_cast<int>(c);
  return -1;
}

std::vector<double> ProbeSeries::series(std::size_t c) const {
  std::vector<double> out(rows());
  for (std::size_t r = 0; r < rows(); ++r) out[r] = at(r, c);
  return out;
}

double probe_field_value(ProbeField f, const SymTensor& s, double plastic_strain, const Vec3& v,
                         const Vec3& position) {
  switch (f) {
    case ProbeField::pressure:
      return pressure(s);
    case ProbeField::von_mises:
      return von_mises(s);
    case ProbeField::plastic_strain:
      return plastic_strain;
    case ProbeField::speed:
      return norm(v);
    case ProbeField::vx:
      return v.x;
    case ProbeField::vy:
      return v.y;
    case ProbeField::vz:
      return v.z;
    case ProbeField::x:
      return position.x;
    case ProbeField::y:
      return position.y;
    case ProbeField::z:
      return position.z;
  }
  return std::nan("");
}

}  // namespace afemp::core
