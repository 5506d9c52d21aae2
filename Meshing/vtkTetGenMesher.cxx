#include "vtkTetGenMesher.h"

#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellType.h"
#include "vtkDoubleArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTetra.h"
#include "vtkUnstructuredGrid.h"

#include <tetgen.h> // TETLIBRARY comes with the TetGen::TetGen target: errors throw an int

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <new>
#include <sstream>
#include <string>
#include <vector>

namespace
{
// A triangle smaller than this fraction of the squared bounding diagonal counts as degenerate,
// and a surface enclosing less than this fraction of the cubed diagonal as flat.
constexpr double DegenerateAreaFraction = 1e-14;
constexpr double DegenerateVolumeFraction = 1e-12;

// TetGen's -a bound over its mean tetrahedron volume, measured with -q1.414 on spheres whose
// triangles are no larger than the tetrahedra (so that the volume bound, not the surface, sets
// the size): 2.2 to 2.6 from 10^5 to 10^6 tetrahedra. See vtkTetGenMesher::GetMeanVolumeFactor().
constexpr double MeanVolumeFactor = 2.4;

/// The surface handed to TetGen: the points the triangles use, renumbered from 0.
struct Surface
{
  std::vector<double> Coordinates; // 3 per point
  std::vector<int> Triangles;      // 3 per triangle, into Coordinates
  double Diagonal = 0.0;
};

std::string Plural(std::size_t count, const char* noun)
{
  std::ostringstream text;
  text << count << " " << noun << (count == 1 ? "" : "s");
  return text.str();
}

/// Triangles of the input, with an error for anything that is not one.
bool CollectTriangles(vtkPolyData* input, Surface& surface, std::string& error)
{
  const vtkIdType numberOfPoints = input->GetNumberOfPoints();
  if (numberOfPoints == 0 || input->GetNumberOfPolys() == 0)
  {
    error = "the input surface has no triangles";
    return false;
  }
  if (numberOfPoints > std::numeric_limits<int>::max() / 4)
  {
    error = "the input surface has more points than TetGen can index";
    return false;
  }
  const vtkIdType others =
    input->GetNumberOfVerts() + input->GetNumberOfLines() + input->GetNumberOfStrips();
  if (others > 0)
  {
    error = "the input has " + Plural(others, "vertex, line or strip cell") +
      "; give a surface of triangles only (vtkTriangleFilter converts strips)";
    return false;
  }
  std::vector<int> newId(numberOfPoints, -1);
  std::size_t notTriangles = 0;
  auto polys = vtk::TakeSmartPointer(input->GetPolys()->NewIterator());
  for (polys->GoToFirstCell(); !polys->IsDoneWithTraversal(); polys->GoToNextCell())
  {
    vtkIdType size;
    const vtkIdType* ids;
    polys->GetCurrentCell(size, ids);
    if (size != 3)
    {
      ++notTriangles;
      continue;
    }
    for (int corner = 0; corner < 3; ++corner)
    {
      int& id = newId[ids[corner]];
      if (id < 0)
      {
        id = static_cast<int>(surface.Coordinates.size() / 3);
        double x[3];
        input->GetPoint(ids[corner], x);
        surface.Coordinates.insert(surface.Coordinates.end(), x, x + 3);
      }
      surface.Triangles.push_back(id);
    }
  }
  if (notTriangles > 0)
  {
    error = "the input has " + Plural(notTriangles, "polygon") +
      " that are not triangles; triangulate them first (vtkTriangleFilter)";
    return false;
  }
  surface.Diagonal = input->GetLength();
  return true;
}

const double* Corner(const Surface& surface, std::size_t triangle, int corner)
{
  return &surface.Coordinates[3 * surface.Triangles[3 * triangle + corner]];
}

/// Triangles with a repeated corner or (almost) no area.
bool CheckTriangles(const Surface& surface, std::string& error)
{
  const double minimumDoubleArea =
    2.0 * DegenerateAreaFraction * surface.Diagonal * surface.Diagonal;
  std::size_t degenerate = 0;
  const std::size_t count = surface.Triangles.size() / 3;
  for (std::size_t t = 0; t < count; ++t)
  {
    double ab[3], ac[3], normal[3];
    vtkMath::Subtract(Corner(surface, t, 1), Corner(surface, t, 0), ab);
    vtkMath::Subtract(Corner(surface, t, 2), Corner(surface, t, 0), ac);
    vtkMath::Cross(ab, ac, normal);
    if (!(vtkMath::Norm(normal) > minimumDoubleArea)) // twice the area
    {
      ++degenerate;
    }
  }
  if (degenerate > 0)
  {
    error = "the surface has " + Plural(degenerate, "degenerate triangle") +
      " (repeated or collinear corners, no area); remove them (vtkCleanPolyData)";
    return false;
  }
  return true;
}

/// A closed, manifold, consistently oriented surface uses each edge exactly twice, once in each
/// direction.
bool CheckEdges(const Surface& surface, std::string& error)
{
  // Key: the edge's smaller id in the high bits, the larger in the low bits; the lowest bit of
  // the record says whether the triangle runs the edge from the smaller id to the larger.
  std::vector<std::uint64_t> edges;
  edges.reserve(surface.Triangles.size());
  const std::size_t count = surface.Triangles.size() / 3;
  for (std::size_t t = 0; t < count; ++t)
  {
    for (int corner = 0; corner < 3; ++corner)
    {
      const std::uint64_t from = static_cast<std::uint64_t>(surface.Triangles[3 * t + corner]);
      const std::uint64_t to =
        static_cast<std::uint64_t>(surface.Triangles[3 * t + (corner + 1) % 3]);
      const std::uint64_t low = std::min(from, to);
      const std::uint64_t high = std::max(from, to);
      edges.push_back((low << 33) | (high << 1) | (from < to ? 1u : 0u));
    }
  }
  std::sort(edges.begin(), edges.end());
  std::size_t open = 0, nonManifold = 0, misoriented = 0;
  for (std::size_t first = 0; first < edges.size();)
  {
    std::size_t last = first;
    while (last < edges.size() && (edges[last] >> 1) == (edges[first] >> 1))
    {
      ++last;
    }
    const std::size_t uses = last - first;
    if (uses == 1)
    {
      ++open;
    }
    else if (uses > 2)
    {
      ++nonManifold;
    }
    else if ((edges[first] & 1u) == (edges[first + 1] & 1u))
    {
      ++misoriented;
    }
    first = last;
  }
  if (open > 0)
  {
    error = "the surface is open: " + Plural(open, "boundary edge") +
      " (used by one triangle only); close it, or merge duplicate points (vtkCleanPolyData)";
  }
  else if (nonManifold > 0)
  {
    error = "the surface is not manifold: " + Plural(nonManifold, "edge") +
      " shared by more than two triangles";
  }
  else if (misoriented > 0)
  {
    error = "the triangles are not consistently oriented: " + Plural(misoriented, "edge") +
      " run the same way in both triangles (vtkPolyDataNormals with ConsistencyOn fixes it)";
  }
  return error.empty();
}

/// The volume the surface encloses, by the divergence theorem (signed: positive when the
/// triangles face outwards).
double SignedEnclosedVolume(const Surface& surface)
{
  double sixVolume = 0.0;
  const std::size_t count = surface.Triangles.size() / 3;
  for (std::size_t t = 0; t < count; ++t)
  {
    double normal[3];
    vtkMath::Cross(Corner(surface, t, 1), Corner(surface, t, 2), normal);
    sixVolume += vtkMath::Dot(Corner(surface, t, 0), normal);
  }
  return sixVolume / 6.0;
}

void FillTetGenInput(const Surface& surface, tetgenio& in)
{
  in.firstnumber = 0;
  in.numberofpoints = static_cast<int>(surface.Coordinates.size() / 3);
  in.pointlist = new REAL[surface.Coordinates.size()];
  std::copy(surface.Coordinates.begin(), surface.Coordinates.end(), in.pointlist);
  in.numberoffacets = static_cast<int>(surface.Triangles.size() / 3);
  in.facetlist = new tetgenio::facet[in.numberoffacets];
  for (int f = 0; f < in.numberoffacets; ++f)
  {
    tetgenio::facet& facet = in.facetlist[f];
    facet.numberofpolygons = 1;
    facet.polygonlist = new tetgenio::polygon[1];
    facet.numberofholes = 0;
    facet.holelist = nullptr;
    tetgenio::polygon& polygon = facet.polygonlist[0];
    polygon.numberofvertices = 3;
    polygon.vertexlist = new int[3];
    std::copy_n(&surface.Triangles[3 * static_cast<std::size_t>(f)], 3, polygon.vertexlist);
  }
}

std::string TetGenErrorMessage(int code)
{
  switch (code)
  {
    case 1:
      return "TetGen ran out of memory";
    case 2:
      return "TetGen failed with an internal error";
    case 3:
      return "the surface intersects itself (TetGen found intersecting triangles)";
    case 4:
      return "the surface has a feature too small for TetGen's tolerance";
    case 5:
      return "the surface has two facets too close to each other for TetGen";
    case 10:
      return "TetGen rejected the input surface";
    default:
      return "TetGen failed with error code " + std::to_string(code);
  }
}

bool RunTetGen(const std::string& switches, tetgenio& in, tetgenio& out, std::string& error)
{
  std::vector<char> arguments(switches.begin(), switches.end());
  arguments.push_back('\0');
  try
  {
    tetrahedralize(arguments.data(), &in, &out);
  }
  catch (int code)
  {
    error = TetGenErrorMessage(code);
    return false;
  }
  catch (const std::bad_alloc&)
  {
    error = TetGenErrorMessage(1);
    return false;
  }
  if (out.numberoftetrahedra <= 0 || out.numberofcorners < 4)
  {
    error = "TetGen produced no tetrahedra";
    return false;
  }
  return true;
}

/// TetGen's tetrahedra as VTK_TETRA cells, each turned positive if TetGen's is not.
void CopyTetGenOutput(const tetgenio& out, vtkUnstructuredGrid* output)
{
  vtkNew<vtkDoubleArray> coordinates;
  coordinates->SetNumberOfComponents(3);
  coordinates->SetNumberOfTuples(out.numberofpoints);
  std::copy_n(
    out.pointlist, 3 * static_cast<std::size_t>(out.numberofpoints), coordinates->GetPointer(0));
  vtkNew<vtkPoints> points;
  points->SetData(coordinates);

  const vtkIdType count = out.numberoftetrahedra;
  const int stride = out.numberofcorners; // 4, or 10 for second order (not asked for)
  vtkNew<vtkIdTypeArray> offsets;
  offsets->SetNumberOfValues(count + 1);
  vtkNew<vtkIdTypeArray> connectivity;
  connectivity->SetNumberOfValues(4 * count);
  vtkIdType* ids = connectivity->GetPointer(0);
  for (vtkIdType t = 0; t < count; ++t)
  {
    const int* tet = out.tetrahedronlist + stride * t;
    vtkIdType* cell = ids + 4 * t;
    std::copy_n(tet, 4, cell);
    if (vtkTetra::ComputeVolume(out.pointlist + 3 * tet[0], out.pointlist + 3 * tet[1],
          out.pointlist + 3 * tet[2], out.pointlist + 3 * tet[3]) < 0.0)
    {
      std::swap(cell[2], cell[3]);
    }
    offsets->SetValue(t, 4 * t);
  }
  offsets->SetValue(count, 4 * count);
  vtkNew<vtkCellArray> cells;
  cells->SetData(offsets, connectivity);
  output->SetPoints(points);
  output->SetCells(VTK_TETRA, cells);
}
} // namespace

vtkStandardNewMacro(vtkTetGenMesher);

vtkTetGenMesher::vtkTetGenMesher() = default;

vtkTetGenMesher::~vtkTetGenMesher() = default;

double vtkTetGenMesher::GetMeanVolumeFactor()
{
  return MeanVolumeFactor;
}

const char* vtkTetGenMesher::GetTetGenSwitches() const
{
  return this->Switches.c_str();
}

int vtkTetGenMesher::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
  return 1;
}

double vtkTetGenMesher::ComputeMaximumVolume(double enclosedVolume) const
{
  double maximumVolume = this->MaximumVolume;
  if (this->TargetNumberOfCells > 0)
  {
    const double fromTarget =
      MeanVolumeFactor * enclosedVolume / static_cast<double>(this->TargetNumberOfCells);
    maximumVolume = maximumVolume > 0.0 ? std::min(maximumVolume, fromTarget) : fromTarget;
  }
  return maximumVolume;
}

void vtkTetGenMesher::ComposeSwitches(double maximumVolume)
{
  // p: the input is a piecewise linear complex; z: numbered from 0; Q/V: quiet or verbose.
  std::ostringstream switches;
  switches.precision(10);
  switches << "pz" << (this->Verbose ? "V" : "Q");
  if (this->RadiusEdgeRatio > 0.0)
  {
    switches << "q" << this->RadiusEdgeRatio;
    if (this->MinimumDihedralAngle > 0.0)
    {
      switches << "/" << this->MinimumDihedralAngle;
    }
  }
  if (maximumVolume > 0.0)
  {
    switches << "a" << maximumVolume;
  }
  this->Switches = switches.str();
}

int vtkTetGenMesher::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector);
  this->EnclosedVolume = 0.0;
  this->AppliedMaximumVolume = 0.0;
  this->Switches.clear();
  if (!input)
  {
    vtkErrorMacro("No input surface: connect a vtkPolyData of triangles.");
    return 0;
  }

  Surface surface;
  std::string error;
  if (!CollectTriangles(input, surface, error) || !CheckTriangles(surface, error) ||
    !CheckEdges(surface, error))
  {
    vtkErrorMacro("Cannot mesh the input: " << error << ".");
    return 0;
  }
  const double volume = std::abs(SignedEnclosedVolume(surface));
  if (!(volume > DegenerateVolumeFraction * std::pow(surface.Diagonal, 3)))
  {
    vtkErrorMacro("Cannot mesh the input: the surface encloses no volume (" << volume << ").");
    return 0;
  }
  this->EnclosedVolume = volume;

  this->AppliedMaximumVolume = this->ComputeMaximumVolume(volume);
  this->ComposeSwitches(this->AppliedMaximumVolume);

  tetgenio in, out;
  FillTetGenInput(surface, in);
  surface = Surface();
  this->UpdateProgress(0.05);
  if (!RunTetGen(this->Switches, in, out, error))
  {
    vtkErrorMacro("Cannot mesh the input: " << error << " (switches " << this->Switches << ").");
    return 0;
  }
  this->UpdateProgress(0.9);
  CopyTetGenOutput(out, output);
  return 1;
}

void vtkTetGenMesher::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "TargetNumberOfCells: " << this->TargetNumberOfCells << "\n";
  os << indent << "MaximumVolume: " << this->MaximumVolume << "\n";
  os << indent << "RadiusEdgeRatio: " << this->RadiusEdgeRatio << "\n";
  os << indent << "MinimumDihedralAngle: " << this->MinimumDihedralAngle << "\n";
  os << indent << "Verbose: " << (this->Verbose ? "On" : "Off") << "\n";
  os << indent << "EnclosedVolume: " << this->EnclosedVolume << "\n";
  os << indent << "AppliedMaximumVolume: " << this->AppliedMaximumVolume << "\n";
  os << indent << "TetGenSwitches: " << this->Switches << "\n";
}
