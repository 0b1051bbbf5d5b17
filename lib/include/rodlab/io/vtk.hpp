#pragma once
// ParaView output: VTK's XML PolyData (.vtp) and its collection file (.pvd), written as text
// ("ascii" data arrays, full double precision), exactly the format of VTK's own
// vtkXMLPolyDataWriter and vtkPVDReader ("VTK File Formats", VTK User's Guide 11th ed., 19.3;
// docs/visualisation.md). No VTK library is needed to write it.
//
// A polydata here is a set of points with named point arrays and one polyline or none:
//   <VTKFile type="PolyData" version="1.0" byte_order="LittleEndian" header_type="UInt64">
//     <PolyData>
//       <FieldData> TimeValue (the time, for ParaView's animation) and scalars </FieldData>
//       <Piece NumberOfPoints="n" NumberOfVerts=".." NumberOfLines=".." ...>
//       <PointData> one DataArray per named array, NumberOfComponents 1 or 3 </PointData>
//       <Points> the coordinates </Points>
//       <Verts> or <Lines>: connectivity and offsets </...>
//     </Piece></PolyData>
//   </VTKFile>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rodlab/lie/se3.hpp"

namespace rodlab::io {

/// A point array: 1 (scalar) or 3 (vector) components per point.
struct VtkArray {
  std::string name;
  int components = 1;
  std::vector<double> values;  ///< components x points, point by point
};

struct VtkPolyData {
  std::vector<lie::Vector3> points;
  /// Polylines through the points, each a list of point indices (a rod's centreline, an
  /// actuator's path); none: the points are vertices (a point cloud).
  std::vector<std::vector<int>> lines;
  std::vector<VtkArray> point_data;
  /// Scalars of the whole data set (FieldData), e.g. the rod's radius; "TimeValue" is added
  /// when `time` is set.
  std::vector<std::pair<std::string, double>> field_data;
  std::optional<double> time;

  /// Adds a scalar array (one value per point).
  void add_scalars(std::string name, std::vector<double> values);
  /// Adds a vector array (one 3-vector per point).
  void add_vectors(std::string name, const std::vector<lie::Vector3>& values);
};

/// The .vtp text of `data`. Throws std::invalid_argument when an array's size is not
/// components x points or a line names a point that does not exist.
std::string vtp_text(const VtkPolyData& data);

/// One file of a collection: its time, its part (ParaView shows parts as blocks) and its path
/// relative to the .pvd.
struct VtkCollectionEntry {
  double time = 0.0;
  int part = 0;
  std::string file;
};

/// The .pvd text listing `entries`.
std::string pvd_text(const std::vector<VtkCollectionEntry>& entries);

}  // namespace rodlab::io
