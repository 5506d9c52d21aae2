/**
 * @class   vtkTetrahedralMesh
 * @brief   the tetrahedra, points and scalars of an unstructured volume, prepared on the CPU
 *
 * Turns a mapper's input into what the mappers draw: point coordinates
 * shifted and scaled to O(1) (so that float precision holds for coordinates near 1e30 or
 * 1e-30), the scalar of every point (or every tetrahedron, for cell data) mapped to [0, 1]
 * over its finite range, and four point ids per tetrahedron. Other linear and quadratic 3D
 * cells are split into tetrahedra by vtkDataSetTriangleFilter when the input changes. The input
 * is never modified. Tetrahedra whose coordinates or scalars are not finite are left out.
 *
 * Shared by the module's mappers (vtkTetrahedralVolumeMapper owns one); vtkSPTMeshBuffers puts
 * it on the GPU for SPT. Not wrapped.
 */

#ifndef vtkTetrahedralMesh_h
#define vtkTetrahedralMesh_h

#include "SPTRenderingCoreModule.h" // For export macro
#include "vtkObject.h"
#include "vtkSmartPointer.h" // For Tetrahedralize()
#include "vtkTimeStamp.h"    // For the caches

#include <string> // For the array name
#include <vector> // For the CPU copies

class vtkDataArray;
class vtkDataSet;
class vtkIdList;
class vtkMatrix4x4;

class SPTRENDERINGCORE_EXPORT vtkTetrahedralMesh : public vtkObject
{
public:
  static vtkTetrahedralMesh* New();
  vtkTypeMacro(vtkTetrahedralMesh, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * How a scalar is chosen from the input, as vtkAbstractVolumeMapper describes it, and how a
   * multi-component array becomes one scalar (component < 0: magnitude).
   */
  struct ScalarSelection
  {
    int ScalarMode = 0;
    int ArrayAccessMode = 0;
    int ArrayId = -1;
    std::string ArrayName;
    int Component = -1;
    bool operator==(const ScalarSelection& o) const
    {
      return ScalarMode == o.ScalarMode && ArrayAccessMode == o.ArrayAccessMode &&
        ArrayId == o.ArrayId && ArrayName == o.ArrayName && Component == o.Component;
    }
  };

  /**
   * Rebuild the CPU arrays if the input, its scalars or the selection changed. Returns false,
   * after reporting the reason with vtkErrorMacro on the caller, when the input cannot be
   * rendered; the reason is also kept in GetLastError().
   */
  bool Update(vtkDataSet* input, const ScalarSelection& selection);
  const std::string& GetLastError() const { return this->LastError; }

  /**
   * The frame shared by the pieces of one data set (ranks of a parallel render): the bounds
   * the coordinates are normalized by and the scalar range mapped to [0, 1], instead of the
   * input's own, so that every piece has the same coordinates and table coordinates as the
   * whole. nullptr (the default) uses the input's own. A change rebuilds at the next Update().
   */
  void SetSharedFrame(const double* bounds, const double* scalarRange);

  /**
   * Number the tetrahedra for the random numbers by the input's global cell ids (the cell
   * data's GlobalIds), when it has them: a tetrahedron of cell g gets g, the j-th further
   * tetrahedron of a split cell g + j * 0x9E3779B9 (mod 2^32). Pieces of one data set then
   * draw the random numbers of the whole. Off by default (the ids are the tetrahedra's
   * indices); a change rebuilds at the next Update().
   */
  void SetUseGlobalIds(bool use);

  ///@{
  /// What Update() found.
  vtkIdType GetNumberOfTetrahedra() const { return vtkIdType(this->Tetrahedra.size() / 4); }
  vtkIdType GetNumberOfPoints() const { return vtkIdType(this->Points.size() / 3); }
  bool GetCellScalars() const { return this->CellScalars; }
  const double* GetScalarRange() const { return this->ScalarRange; }
  /// Point coordinates are (x - center) / Scale (GetNormalizationMatrix()).
  double GetScale() const { return this->Scale; }
  /// The bounds of the points, in the normalized units of the coordinates.
  const double* GetNormalizedBounds() const { return this->NormalizedBounds; }
  /// Longest tetrahedron edge, in the normalized units of the coordinates.
  double GetMaxEdgeLength() const { return this->MaxEdgeLength; }
  vtkIdType GetNumberOfSkippedCells() const { return this->SkippedCells; }
  const std::vector<float>& GetPoints() const { return this->Points; }
  const std::vector<float>& GetScalars() const { return this->Scalars; }
  const std::vector<unsigned int>& GetTetrahedra() const { return this->Tetrahedra; }
  /// The tetrahedra's ids for the random numbers; empty unless global ids are used and found.
  const std::vector<unsigned int>& GetRandomIds() const { return this->RandomIds; }
  /// The bounds of the input's finite points and the range of its finite scalars, whatever
  /// the shared frame (min > max: none).
  const double* GetDataBounds() const { return this->DataBounds; }
  const double* GetDataScalarRange() const { return this->DataScalarRange; }
  vtkMTimeType GetBuildTime() const { return this->BuildTime.GetMTime(); }
  ///@}

  /// The matrix from the normalized coordinates of the points to model coordinates.
  void GetNormalizationMatrix(vtkMatrix4x4* matrix) const;

protected:
  vtkTetrahedralMesh();
  ~vtkTetrahedralMesh() override;

private:
  vtkTetrahedralMesh(const vtkTetrahedralMesh&) = delete;
  void operator=(const vtkTetrahedralMesh&) = delete;

  void Clear(); // nothing to draw
  bool Fail(const std::string& reason);
  bool CheckConnectivity(vtkDataSet* input);
  // The input split into tetrahedra (or the input itself, if it holds nothing else), and in
  // `scalars` the selected array of that output; `ids` (global cell ids, or null) likewise.
  vtkSmartPointer<vtkDataSet> Tetrahedralize(vtkDataSet* input,
    vtkSmartPointer<vtkDataArray>& scalars, bool cellScalars, vtkSmartPointer<vtkDataArray>& ids);
  // RandomIds from the global cell ids of the tetrahedra kept.
  void NumberByGlobalIds(vtkDataArray* ids, const std::vector<vtkIdType>& keptCells);
  // `keptCells`: the cells of `tetrahedra` that were kept, in order.
  bool Extract(vtkDataSet* tetrahedra, vtkDataArray* scalars, bool cellScalars, int component,
    std::vector<vtkIdType>& keptCells);
  // Center, Scale, NormalizedBounds and Points from the input's coordinates and finite bounds.
  void Normalize(const std::vector<double>& coordinates, const double bounds[6]);
  // The valid tetrahedra, their cell scalars and MaxEdgeLength; false (after Fail) on bad ids.
  bool ExtractTetrahedra(vtkDataSet* tetrahedra, const std::vector<double>& values,
    const std::vector<char>& pointIsValid, std::vector<vtkIdType>& keptCells);
  void AddTetrahedron(vtkIdList* ids);

  std::string LastError;
  std::vector<float> Points;
  std::vector<float> Scalars;
  std::vector<unsigned int> Tetrahedra;
  std::vector<unsigned int> RandomIds;
  bool CellScalars = false;
  double ScalarRange[2] = { 0.0, 1.0 };
  double Center[3] = { 0.0, 0.0, 0.0 };
  double Scale = 1.0;
  double NormalizedBounds[6] = { 0.0, 0.0, 0.0, 0.0, 0.0, 0.0 };
  double MaxEdgeLength = 0.0;
  vtkIdType SkippedCells = 0;
  double DataBounds[6] = { 0.0, -1.0, 0.0, -1.0, 0.0, -1.0 };
  double DataScalarRange[2] = { 0.0, -1.0 };
  bool HasSharedFrame = false;
  double SharedBounds[6] = { 0.0, 0.0, 0.0, 0.0, 0.0, 0.0 };
  double SharedScalarRange[2] = { 0.0, 0.0 };
  bool UseGlobalIds = false;
  vtkTimeStamp OptionsTime; // the shared frame or the numbering changed

  vtkDataSet* LastInput = nullptr; // identity only, never dereferenced
  vtkDataArray* LastScalars = nullptr;
  ScalarSelection LastSelection;
  vtkTimeStamp BuildTime;
};

#endif
