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

#include "SPTRenderingModule.h" // For export macro
#include "vtkObject.h"
#include "vtkSmartPointer.h" // For Tetrahedralize()
#include "vtkTimeStamp.h"    // For the caches

#include <string> // For the array name
#include <vector> // For the CPU copies

class vtkDataArray;
class vtkDataSet;
class vtkIdList;
class vtkMatrix4x4;

class SPTRENDERING_EXPORT vtkTetrahedralMesh : public vtkObject
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

  ///@{
  /**
   * What Update() found.
   */
  vtkIdType GetNumberOfTetrahedra() const { return vtkIdType(this->Tetrahedra.size() / 4); }
  vtkIdType GetNumberOfPoints() const { return vtkIdType(this->Points.size() / 3); }
  bool GetCellScalars() const { return this->CellScalars; }
  const double* GetScalarRange() const { return this->ScalarRange; }
  /// Point coordinates are (x - Center) / Scale.
  const double* GetCenter() const { return this->Center; }
  double GetScale() const { return this->Scale; }
  /// The bounds of the points, in the normalized units of the coordinates.
  const double* GetNormalizedBounds() const { return this->NormalizedBounds; }
  /// Longest tetrahedron edge, in the normalized units of the coordinates.
  double GetMaxEdgeLength() const { return this->MaxEdgeLength; }
  vtkIdType GetNumberOfSkippedCells() const { return this->SkippedCells; }
  const std::vector<float>& GetPoints() const { return this->Points; }
  const std::vector<float>& GetScalars() const { return this->Scalars; }
  const std::vector<unsigned int>& GetTetrahedra() const { return this->Tetrahedra; }
  vtkMTimeType GetBuildTime() const { return this->BuildTime.GetMTime(); }
  ///@}

  /**
   * The matrix from the normalized coordinates of the points to model coordinates.
   */
  void GetNormalizationMatrix(vtkMatrix4x4* matrix) const;

protected:
  vtkTetrahedralMesh();
  ~vtkTetrahedralMesh() override;

private:
  vtkTetrahedralMesh(const vtkTetrahedralMesh&) = delete;
  void operator=(const vtkTetrahedralMesh&) = delete;

  bool Fail(const std::string& reason);
  bool CheckConnectivity(vtkDataSet* input);
  // The input split into tetrahedra (or the input itself, if it holds nothing else), and in
  // `scalars` the selected array of that output.
  vtkSmartPointer<vtkDataSet> Tetrahedralize(
    vtkDataSet* input, vtkSmartPointer<vtkDataArray>& scalars, bool cellScalars);
  bool Extract(vtkDataSet* tetrahedra, vtkDataArray* scalars, bool cellScalars, int component);
  // Center, Scale, NormalizedBounds and Points from the input's coordinates and finite bounds.
  void Normalize(const std::vector<double>& coordinates, const double bounds[6]);
  // The valid tetrahedra, their cell scalars and MaxEdgeLength; false (after Fail) on bad ids.
  bool ExtractTetrahedra(vtkDataSet* tetrahedra, const std::vector<double>& values,
    const std::vector<char>& pointIsValid);
  void AddTetrahedron(vtkIdList* ids);

  std::string LastError;
  std::vector<float> Points;
  std::vector<float> Scalars;
  std::vector<unsigned int> Tetrahedra;
  bool CellScalars = false;
  double ScalarRange[2] = { 0.0, 1.0 };
  double Center[3] = { 0.0, 0.0, 0.0 };
  double Scale = 1.0;
  double NormalizedBounds[6] = { 0.0, 0.0, 0.0, 0.0, 0.0, 0.0 };
  double MaxEdgeLength = 0.0;
  vtkIdType SkippedCells = 0;

  vtkDataSet* LastInput = nullptr; // identity only, never dereferenced
  vtkDataArray* LastScalars = nullptr;
  ScalarSelection LastSelection;
  vtkTimeStamp BuildTime;
};

#endif
