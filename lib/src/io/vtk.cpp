#include "rodlab/io/vtk.hpp"

#include <stdexcept>

#include <fmt/format.h>

#include "rodlab/io/text_format.hpp"

namespace rodlab::io {
namespace {

/// Shortest text that reads back to the same double (fmt's "{}").
void append_numbers(std::string& out, const double* v, std::size_t n, int per_line) {
  for (std::size_t i = 0; i < n; ++i) {
    out += (i % per_line == 0) ? "\n          " : " ";
    fmt::format_to(std::back_inserter(out), "{}", v[i]);
  }
  out += "\n        ";
}

void append_array(std::string& out, const std::string& name, int components,
                  const std::vector<double>& values) {
  fmt::format_to(std::back_inserter(out),
                 "        <DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\" "
                 "format=\"ascii\">",
                 name, components);
  append_numbers(out, values.data(), values.size(), components == 1 ? 6 : components * 2);
  out += "</DataArray>\n";
}

void append_cells(std::string& out, const char* tag, const std::vector<std::vector<int>>& cells) {
  fmt::format_to(std::back_inserter(out), "      <{}>\n", tag);
  out += "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">";
  std::vector<double> connectivity, offsets;
  long end = 0;
  for (const auto& cell : cells) {
    for (int k : cell) connectivity.push_back(k);
    end += static_cast<long>(cell.size());
    offsets.push_back(static_cast<double>(end));
  }
  append_numbers(out, connectivity.data(), connectivity.size(), 12);
  out += "</DataArray>\n";
  out += "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">";
  append_numbers(out, offsets.data(), offsets.size(), 12);
  out += "</DataArray>\n";
  fmt::format_to(std::back_inserter(out), "      </{}>\n", tag);
}


}  // namespace

void VtkPolyData::add_scalars(std::string name, std::vector<double> values) {
  point_data.push_back({std::move(name), 1, std::move(values)});
}

void VtkPolyData::add_vectors(std::string name, const std::vector<lie::Vector3>& values) {
  VtkArray a{std::move(name), 3, {}};
  a.values.reserve(3 * values.size());
  for (const auto& v : values) a.values.insert(a.values.end(), {v[0], v[1], v[2]});
  point_data.push_back(std::move(a));
}

std::string vtp_text(const VtkPolyData& d) {
  const std::size_t n = d.points.size();
  for (const auto& a : d.point_data)
    if (a.components < 1 || a.values.size() != n * static_cast<std::size_t>(a.components))
      throw std::invalid_argument(fmt::format("vtk: array {} has {} values for {} points", a.name,
                                              a.values.size(), n));
  for (const auto& line : d.lines)
    for (int k : line)
      if (k < 0 || static_cast<std::size_t>(k) >= n)
        throw std::invalid_argument(fmt::format("vtk: a line names point {} of {}", k, n));
  std::vector<std::vector<int>> verts;
  if (d.lines.empty())
    for (std::size_t k = 0; k < n; ++k) verts.push_back({static_cast<int>(k)});

  std::string out =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
      "header_type=\"UInt64\">\n  <PolyData>\n";
  auto fields = d.field_data;
  if (d.time) fields.insert(fields.begin(), {"TimeValue", *d.time});
  if (!fields.empty()) {
    out += "    <FieldData>\n";
    for (const auto& [name, value] : fields) {
      fmt::format_to(std::back_inserter(out),
                     "      <DataArray type=\"Float64\" Name=\"{}\" NumberOfTuples=\"1\" "
                     "format=\"ascii\">",
                     xml_escape(name));
      append_numbers(out, &value, 1, 1);
      out += "</DataArray>\n";
    }
    out += "    </FieldData>\n";
  }
  fmt::format_to(std::back_inserter(out),
                 "    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"{}\" NumberOfLines=\"{}\" "
                 "NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n",
                 n, verts.size(), d.lines.size());
  out += "      <PointData>\n";
  for (const auto& a : d.point_data) append_array(out, xml_escape(a.name), a.components, a.values);
  out += "      </PointData>\n      <Points>\n";
  std::vector<double> xyz;
  xyz.reserve(3 * n);
  for (const auto& p : d.points) xyz.insert(xyz.end(), {p[0], p[1], p[2]});
  append_array(out, "Points", 3, xyz);
  out += "      </Points>\n";
  append_cells(out, "Verts", verts);
  append_cells(out, "Lines", d.lines);
  out += "    </Piece>\n  </PolyData>\n</VTKFile>\n";
  return out;
}

std::string pvd_text(const std::vector<VtkCollectionEntry>& entries) {
  std::string out =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      "  <Collection>\n";
  for (const auto& e : entries)
    fmt::format_to(std::back_inserter(out),
                   "    <DataSet timestep=\"{}\" group=\"\" part=\"{}\" file=\"{}\"/>\n", e.time,
                   e.part, xml_escape(e.file));
  out += "  </Collection>\n</VTKFile>\n";
  return out;
}

}  // namespace rodlab::io
