#include "vtkTetrahedralMesh.h"

#include "vtkAbstractMapper.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkDataArray.h"
#include "vtkDataSetTriangleFilter.h"
#include "vtkFieldData.h"
#include "vtkGenericCell.h"
#include "vtkIdList.h"
#include "vtkMatrix4x4.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

namespace
{
// The name of the scalars handed to the split into tetrahedra.
constexpr const char* SplitScalarsName = "vtkTetrahedralMesh scalars";
// The name of the global cell ids handed to the split.
constexpr const char* SplitIdsName = "vtkTetrahedralMesh ids";
// What the further tetrahedra of a split cell add to its global id (2^32 / golden ratio).
constexpr unsigned int SplitIdStride = 0x9E3779B9u;

double ScalarOf(vtkDataArray* array, vtkIdType tuple, int component)
{
  if (component >= 0)
  {
    return array->GetComponent(tuple, component);
  }
  const int n = array->GetNumberOfComponents();
  if (n == 1)
  {
    return array->GetComponent(tuple, 0);
  }
  double sum = 0.0;
  for (int c = 0; c < n; ++c)
  {
    const double v = array->GetComponent(tuple, c);
    sum += v * v;
  }
  return std::sqrt(sum);
}

// Why the scalars cannot be rendered, or an empty string if they can.
std::string CheckScalars(vtkDataSet* input, vtkDataArray* scalars, int cellFlag,
  const vtkTetrahedralMesh::ScalarSelection& selection)
{
  std::ostringstream reason;
  if (!scalars)
  {
    reason << "The input has no scalars to render";
    if (!selection.ArrayName.empty() || selection.ArrayId >= 0)
    {
      reason << " (the selected array '" << selection.ArrayName << "', id " << selection.ArrayId
             << ", is not in its point or cell data)";
    }
    reason << ". Select a point or cell array with SelectScalarArray() and SetScalarMode().";
    return reason.str();
  }
  if (cellFlag != 0 && cellFlag != 1)
  {
    return "Field-data scalars cannot be volume rendered; use point or cell data.";
  }
  if (selection.Component >= scalars->GetNumberOfComponents())
  {
    reason << "Component " << selection.Component << " was selected, but the array '"
           << (scalars->GetName() ? scalars->GetName() : "") << "' has only "
           << scalars->GetNumberOfComponents() << " component(s).";
    return reason.str();
  }
  const vtkIdType needed = cellFlag == 1 ? input->GetNumberOfCells() : input->GetNumberOfPoints();
  if (scalars->GetNumberOfTuples() < needed)
  {
    reason << "The scalar array '" << (scalars->GetName() ? scalars->GetName() : "") << "' has "
           << scalars->GetNumberOfTuples() << " values, but the grid has " << needed
           << (cellFlag == 1 ? " cells." : " points.");
    return reason.str();
  }
  return std::string();
}

// Why the cell data's GlobalIds cannot number the cells (too few values), or nothing.
std::string CheckGlobalIds(vtkDataArray* ids, vtkIdType numberOfCells)
{
  if (!ids || ids->GetNumberOfTuples() >= numberOfCells)
  {
    return std::string();
  }
  return "The cell data GlobalIds array '" + std::string(ids->GetName() ? ids->GetName() : "") +
    "' has " + std::to_string(ids->GetNumberOfTuples()) + " values for " +
    std::to_string(numberOfCells) + " cells.";
}

// The points' coordinates, whether each is finite, and the bounds of the finite ones (empty,
// min > max, if none is).
std::vector<double> FiniteCoordinates(
  vtkDataSet* tetrahedra, std::vector<char>& pointIsValid, double bounds[6])
{
  const vtkIdType numberOfPoints = tetrahedra->GetNumberOfPoints();
  std::vector<double> coordinates(3 * numberOfPoints);
  pointIsValid.assign(numberOfPoints, 1);
  for (int a = 0; a < 3; ++a)
  {
    bounds[2 * a] = VTK_DOUBLE_MAX;
    bounds[2 * a + 1] = VTK_DOUBLE_MIN;
  }
  for (vtkIdType i = 0; i < numberOfPoints; ++i)
  {
    double* p = &coordinates[3 * i];
    tetrahedra->GetPoint(i, p);
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
    {
      pointIsValid[i] = 0;
      continue;
    }
    for (int a = 0; a < 3; ++a)
    {
      bounds[2 * a] = std::min(bounds[2 * a], p[a]);
      bounds[2 * a + 1] = std::max(bounds[2 * a + 1], p[a]);
    }
  }
  return coordinates;
}

// The scalar of every tuple, and the range of the finite ones ({0, 0} if none is).
std::vector<double> ScalarValues(vtkDataArray* scalars, int component, double range[2])
{
  const vtkIdType numberOfValues = scalars->GetNumberOfTuples();
  std::vector<double> values(numberOfValues);
  range[0] = VTK_DOUBLE_MAX;
  range[1] = VTK_DOUBLE_MIN;
  for (vtkIdType i = 0; i < numberOfValues; ++i)
  {
    values[i] = ScalarOf(scalars, i, component);
    if (std::isfinite(values[i]))
    {
      range[0] = std::min(range[0], values[i]);
      range[1] = std::max(range[1], values[i]);
    }
  }
  if (range[0] > range[1])
  {
    range[0] = range[1] = 0.0; // no finite value: every tetrahedron is left out
  }
  return values;
}

// A scalar as a coordinate of the pre-integration table, [0, 1] over the range.
float ToTable(double value, const double range[2])
{
  const double width = range[1] - range[0];
  return width > 0.0 ? float((value - range[0]) / width) : 0.0f;
}
}

vtkStandardNewMacro(vtkTetrahedralMesh);

vtkTetrahedralMesh::vtkTetrahedralMesh() = default;

vtkTetrahedralMesh::~vtkTetrahedralMesh() = default;

void vtkTetrahedralMesh::SetSharedFrame(const double* bounds, const double* scalarRange)
{
  const bool has = bounds && scalarRange;
  if (has == this->HasSharedFrame &&
    (!has ||
      (std::equal(bounds, bounds + 6, this->SharedBounds) &&
        std::equal(scalarRange, scalarRange + 2, this->SharedScalarRange))))
  {
    return;
  }
  this->HasSharedFrame = has;
  if (has)
  {
    std::copy(bounds, bounds + 6, this->SharedBounds);
    std::copy(scalarRange, scalarRange + 2, this->SharedScalarRange);
  }
  this->OptionsTime.Modified();
}

void vtkTetrahedralMesh::SetUseGlobalIds(bool use)
{
  if (use != this->UseGlobalIds)
  {
    this->UseGlobalIds = use;
    this->OptionsTime.Modified();
  }
}

void vtkTetrahedralMesh::Clear()
{
  this->Points.clear();
  this->Scalars.clear();
  this->Tetrahedra.clear();
  this->RandomIds.clear();
  std::fill(this->DataBounds, this->DataBounds + 6, 0.0);
  this->DataBounds[1] = this->DataBounds[3] = this->DataBounds[5] = -1.0;
  this->DataScalarRange[0] = 0.0;
  this->DataScalarRange[1] = -1.0;
}

bool vtkTetrahedralMesh::Fail(const std::string& reason)
{
  this->LastError = reason;
  this->Clear();
  this->BuildTime.Modified();
  return false;
}

bool vtkTetrahedralMesh::Update(vtkDataSet* input, const ScalarSelection& selection)
{
  if (!input)
  {
    this->LastInput = nullptr;
    return this->Fail("The mapper has no input data set.");
  }
  int cellFlag = -1;
  vtkDataArray* scalars = vtkAbstractMapper::GetScalars(input, selection.ScalarMode,
    selection.ArrayAccessMode, selection.ArrayId, selection.ArrayName.c_str(), cellFlag);
  if (input == this->LastInput && scalars == this->LastScalars &&
    selection == this->LastSelection && this->BuildTime > input->GetMTime() &&
    this->BuildTime > this->OptionsTime && (!scalars || this->BuildTime > scalars->GetMTime()))
  {
    return this->LastError.empty();
  }
  this->LastInput = input;
  this->LastScalars = scalars;
  this->LastSelection = selection;
  this->LastError.clear();
  this->SkippedCells = 0;
  if (input->GetNumberOfCells() == 0)
  {
    // Nothing to draw is not an error.
    this->Clear();
    this->BuildTime.Modified();
    return true;
  }
  const std::string reason = CheckScalars(input, scalars, cellFlag, selection);
  if (!reason.empty())
  {
    return this->Fail(reason);
  }
  if (!this->CheckConnectivity(input))
  {
    return false;
  }
  vtkSmartPointer<vtkDataArray> tetrahedraScalars = scalars;
  vtkSmartPointer<vtkDataArray> ids =
    this->UseGlobalIds ? input->GetCellData()->GetGlobalIds() : nullptr;
  const std::string idsReason = CheckGlobalIds(ids, input->GetNumberOfCells());
  if (!idsReason.empty())
  {
    return this->Fail(idsReason);
  }
  vtkSmartPointer<vtkDataSet> tetrahedra =
    this->Tetrahedralize(input, tetrahedraScalars, cellFlag == 1, ids);
  if (!tetrahedraScalars)
  {
    return this->Fail("The scalars did not survive the split into tetrahedra.");
  }
  std::vector<vtkIdType> keptCells;
  if (!this->Extract(tetrahedra, tetrahedraScalars, cellFlag == 1, selection.Component, keptCells))
  {
    return false;
  }
  this->NumberByGlobalIds(ids, keptCells);
  return true;
}

void vtkTetrahedralMesh::NumberByGlobalIds(
  vtkDataArray* ids, const std::vector<vtkIdType>& keptCells)
{
  this->RandomIds.clear();
  if (!ids || keptCells.empty())
  {
    return;
  }
  // The tetrahedra of one split cell are consecutive cells of the split, with its id.
  this->RandomIds.reserve(keptCells.size());
  size_t k = 0;
  unsigned int inCell = 0;
  for (vtkIdType cell = 0; cell <= keptCells.back(); ++cell)
  {
    const auto id = static_cast<vtkIdType>(ids->GetComponent(cell, 0));
    inCell =
      cell > 0 && id == static_cast<vtkIdType>(ids->GetComponent(cell - 1, 0)) ? inCell + 1 : 0;
    if (keptCells[k] == cell)
    {
      this->RandomIds.push_back(static_cast<unsigned int>(id) + inCell * SplitIdStride);
      ++k;
    }
  }
}

bool vtkTetrahedralMesh::CheckConnectivity(vtkDataSet* input)
{
  // Point ids out of range would crash the triangulation and the GPU draw alike, and so would
  // a cell with fewer points than its type has (the triangulation reads them all).
  vtkUnstructuredGrid* grid = vtkUnstructuredGrid::SafeDownCast(input);
  if (!grid || !grid->GetCells())
  {
    return true;
  }
  const vtkIdType numberOfPoints = grid->GetNumberOfPoints();
  std::map<int, vtkIdType> pointsOfType; // 0: any number (polygons, polyhedra, ...)
  vtkNew<vtkGenericCell> prototype;
  auto cells = vtk::TakeSmartPointer(grid->GetCells()->NewIterator());
  for (cells->GoToFirstCell(); !cells->IsDoneWithTraversal(); cells->GoToNextCell())
  {
    vtkIdType count;
    const vtkIdType* ids;
    cells->GetCurrentCell(count, ids);
    const vtkIdType cellId = cells->GetCurrentCellId();
    const int type = grid->GetCellType(cellId);
    auto expected = pointsOfType.find(type);
    if (expected == pointsOfType.end())
    {
      prototype->SetCellType(type);
      expected = pointsOfType.emplace(type, prototype->GetNumberOfPoints()).first;
    }
    if (expected->second > 0 && count != expected->second)
    {
      std::ostringstream reason;
      reason << "Cell " << cellId << " (VTK cell type " << type << ") has " << count
             << " points; that type has " << expected->second << ".";
      return this->Fail(reason.str());
    }
    for (vtkIdType i = 0; i < count; ++i)
    {
      if (ids[i] < 0 || ids[i] >= numberOfPoints)
      {
        std::ostringstream reason;
        reason << "Cell " << cellId << " refers to point id " << ids[i] << ", but the grid has "
               << numberOfPoints << " points.";
        return this->Fail(reason.str());
      }
    }
  }
  return true;
}

vtkSmartPointer<vtkDataSet> vtkTetrahedralMesh::Tetrahedralize(vtkDataSet* input,
  vtkSmartPointer<vtkDataArray>& scalars, bool cellScalars, vtkSmartPointer<vtkDataArray>& ids)
{
  vtkUnstructuredGrid* grid = vtkUnstructuredGrid::SafeDownCast(input);
  if (grid)
  {
    vtkUnsignedCharArray* types = grid->GetDistinctCellTypesArray();
    if (grid->GetNumberOfCells() == 0 ||
      (types && types->GetNumberOfTuples() == 1 && types->GetValue(0) == VTK_TETRA))
    {
      return input;
    }
  }
  // The split sees the structure and the selected scalars only (under a name of its own, the
  // values shared with the input's array): the input's other arrays, which the filter would
  // copy, may not even match the grid.
  auto bare = vtk::TakeSmartPointer(input->NewInstance());
  bare->CopyStructure(input);
  const auto share = [](vtkDataArray* array, const char* name, vtkFieldData* to)
  {
    auto shared = vtk::TakeSmartPointer(array->NewInstance());
    shared->ShallowCopy(array);
    shared->SetName(name);
    to->AddArray(shared);
  };
  share(scalars, SplitScalarsName,
    cellScalars ? static_cast<vtkFieldData*>(bare->GetCellData()) : bare->GetPointData());
  if (ids)
  {
    share(ids, SplitIdsName, bare->GetCellData());
  }
  vtkNew<vtkDataSetTriangleFilter> triangulate;
  triangulate->SetInputData(bare);
  triangulate->TetrahedraOnlyOn();
  triangulate->Update();
  // A copy, so that the filter (and through it the input) is not kept alive.
  auto output = vtkSmartPointer<vtkUnstructuredGrid>::New();
  output->ShallowCopy(triangulate->GetOutput());
  vtkFieldData* attributes = cellScalars ? static_cast<vtkFieldData*>(output->GetCellData())
                                         : static_cast<vtkFieldData*>(output->GetPointData());
  scalars = attributes->GetArray(SplitScalarsName);
  ids = ids ? output->GetCellData()->GetArray(SplitIdsName) : nullptr;
  return output;
}

bool vtkTetrahedralMesh::Extract(vtkDataSet* tetrahedra, vtkDataArray* scalars, bool cellScalars,
  int component, std::vector<vtkIdType>& keptCells)
{
  const vtkIdType numberOfPoints = tetrahedra->GetNumberOfPoints();
  if (numberOfPoints > vtkIdType(std::numeric_limits<unsigned int>::max()))
  {
    return this->Fail("The mesh has more points than 32-bit indices can address.");
  }
  this->CellScalars = cellScalars;

  // Finite coordinates and scalar values; anything else leaves its tetrahedra out.
  std::vector<char> pointIsValid;
  double bounds[6];
  const std::vector<double> coordinates = FiniteCoordinates(tetrahedra, pointIsValid, bounds);
  const std::vector<double> values = ScalarValues(scalars, component, this->ScalarRange);
  std::copy(bounds, bounds + 6, this->DataBounds);
  std::copy(this->ScalarRange, this->ScalarRange + 2, this->DataScalarRange);
  if (this->HasSharedFrame)
  {
    std::copy(this->SharedBounds, this->SharedBounds + 6, bounds);
    std::copy(this->SharedScalarRange, this->SharedScalarRange + 2, this->ScalarRange);
  }
  this->Normalize(coordinates, bounds);

  this->Scalars.clear();
  if (!cellScalars)
  {
    const vtkIdType numberOfValues = vtkIdType(values.size());
    this->Scalars.resize(numberOfPoints);
    for (vtkIdType i = 0; i < numberOfPoints; ++i)
    {
      pointIsValid[i] = pointIsValid[i] && i < numberOfValues && std::isfinite(values[i]);
      this->Scalars[i] = pointIsValid[i] ? ToTable(values[i], this->ScalarRange) : 0.0f;
    }
  }
  if (!this->ExtractTetrahedra(tetrahedra, values, pointIsValid, keptCells))
  {
    return false;
  }
  this->BuildTime.Modified();
  return true;
}

void vtkTetrahedralMesh::Normalize(const std::vector<double>& coordinates, const double bounds[6])
{
  double diagonal = 0.0;
  for (int a = 0; a < 3; ++a)
  {
    const bool valid = bounds[2 * a] <= bounds[2 * a + 1];
    this->Center[a] = valid ? 0.5 * (bounds[2 * a] + bounds[2 * a + 1]) : 0.0;
    diagonal = std::max(diagonal, valid ? bounds[2 * a + 1] - bounds[2 * a] : 0.0);
  }
  this->Scale = diagonal > 0.0 && std::isfinite(diagonal) ? diagonal : 1.0;
  for (int a = 0; a < 3; ++a)
  {
    const bool empty = bounds[2 * a] > bounds[2 * a + 1];
    this->NormalizedBounds[2 * a] = empty ? 0.0 : (bounds[2 * a] - this->Center[a]) / this->Scale;
    this->NormalizedBounds[2 * a + 1] =
      empty ? 0.0 : (bounds[2 * a + 1] - this->Center[a]) / this->Scale;
  }
  this->Points.resize(coordinates.size());
  for (size_t i = 0; i < coordinates.size(); ++i)
  {
    this->Points[i] = float((coordinates[i] - this->Center[i % 3]) / this->Scale);
  }
}

bool vtkTetrahedralMesh::ExtractTetrahedra(vtkDataSet* tetrahedra,
  const std::vector<double>& values, const std::vector<char>& pointIsValid,
  std::vector<vtkIdType>& keptCells)
{
  const vtkIdType numberOfPoints = tetrahedra->GetNumberOfPoints();
  const vtkIdType numberOfValues = vtkIdType(values.size());
  const vtkIdType numberOfCells = tetrahedra->GetNumberOfCells();
  this->Tetrahedra.clear();
  this->Tetrahedra.reserve(4 * numberOfCells);
  if (this->CellScalars)
  {
    this->Scalars.reserve(numberOfCells);
  }
  this->MaxEdgeLength = 0.0;
  vtkNew<vtkIdList> ids;
  for (vtkIdType cell = 0; cell < numberOfCells; ++cell)
  {
    if (tetrahedra->GetCellType(cell) != VTK_TETRA)
    {
      continue;
    }
    tetrahedra->GetCellPoints(cell, ids);
    const auto outOfRange = [&](vtkIdType id) { return id < 0 || id >= numberOfPoints; };
    if (ids->GetNumberOfIds() != 4 || std::any_of(ids->begin(), ids->end(), outOfRange))
    {
      return this->Fail("The split into tetrahedra made a tetrahedron that is not one (point "
                        "ids missing or out of range); the input's cells are not valid.");
    }
    bool valid = !this->CellScalars || (cell < numberOfValues && std::isfinite(values[cell]));
    for (int v = 0; v < 4 && valid; ++v)
    {
      valid = pointIsValid[ids->GetId(v)] != 0;
    }
    if (!valid)
    {
      ++this->SkippedCells;
      continue;
    }
    this->AddTetrahedron(ids);
    keptCells.push_back(cell);
    if (this->CellScalars)
    {
      this->Scalars.push_back(ToTable(values[cell], this->ScalarRange));
    }
  }
  return true;
}

void vtkTetrahedralMesh::AddTetrahedron(vtkIdList* ids)
{
  for (int v = 0; v < 4; ++v)
  {
    this->Tetrahedra.push_back(static_cast<unsigned int>(ids->GetId(v)));
    const float* p = &this->Points[3 * ids->GetId(v)];
    for (int w = v + 1; w < 4; ++w)
    {
      const float* q = &this->Points[3 * ids->GetId(w)];
      const double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
      this->MaxEdgeLength = std::max(this->MaxEdgeLength, std::sqrt(dx * dx + dy * dy + dz * dz));
    }
  }
}

void vtkTetrahedralMesh::GetNormalizationMatrix(vtkMatrix4x4* matrix) const
{
  matrix->Identity();
  for (int a = 0; a < 3; ++a)
  {
    matrix->SetElement(a, a, this->Scale);
    matrix->SetElement(a, 3, this->Center[a]);
  }
}

void vtkTetrahedralMesh::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "NumberOfTetrahedra: " << this->GetNumberOfTetrahedra() << "\n";
  os << indent << "NumberOfPoints: " << this->GetNumberOfPoints() << "\n";
  os << indent << "CellScalars: " << this->CellScalars << "\n";
  os << indent << "ScalarRange: " << this->ScalarRange[0] << " " << this->ScalarRange[1] << "\n";
  os << indent << "SkippedCells: " << this->SkippedCells << "\n";
}
