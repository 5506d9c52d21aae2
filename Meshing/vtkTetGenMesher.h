/**
 * @class   vtkTetGenMesher
 * @brief   quality tetrahedral mesh of a closed triangulated surface, with TetGen 1.5
 *
 * vtkTetGenMesher fills the region bounded by a closed, manifold, non-self-intersecting
 * triangulated surface (vtkPolyData of triangles) with tetrahedra, using TetGen's constrained
 * Delaunay refinement:
 *
 *   H. Si, "TetGen, a Delaunay-based quality tetrahedral mesh generator", ACM Transactions on
 *   Mathematical Software 41(2), 2015.
 *
 * The output is a vtkUnstructuredGrid of VTK_TETRA cells, every one positively oriented (its
 * fourth point on the side of the first three's right-handed normal), with the surface's
 * vertices among its points. It holds only points and cells; no point or cell data of the input
 * is passed on.
 *
 * The mesh size is set by TargetNumberOfCells (converted to a maximum tetrahedron volume from the
 * volume the surface encloses) or directly by MaximumVolume; the shape of the tetrahedra by
 * RadiusEdgeRatio and MinimumDihedralAngle (TetGen's -q). Without any of them the result is the
 * constrained Delaunay tetrahedralization of the surface's own vertices.
 *
 * The input is checked before TetGen runs, and each problem gives an error naming it and an
 * empty output: no input, cells that are not triangles (vtkTriangleFilter triangulates them),
 * degenerate triangles, an open surface (edges used by one triangle), non-manifold edges (used by
 * more than two) and a surface that encloses no volume. Errors that TetGen finds itself, above
 * all self-intersecting surfaces, are reported the same way; TetGen never ends the process.
 * The input is never modified.
 *
 * TetGen is not thread-safe across instances (it keeps global state for its exact predicates):
 * run one mesher at a time.
 */
#ifndef vtkTetGenMesher_h
#define vtkTetGenMesher_h

#include "SPTMeshingModule.h" // for export macro
#include "vtkUnstructuredGridAlgorithm.h"

#include <string> // For the switches

class SPTMESHING_EXPORT vtkTetGenMesher : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkTetGenMesher* New();
  vtkTypeMacro(vtkTetGenMesher, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * Number of tetrahedra to aim at; 0 (the default) turns it off. It becomes a maximum
   * tetrahedron volume of MeanVolumeFactor x (enclosed volume) / TargetNumberOfCells, so the
   * count is met only approximately (typically within 25 % for smooth surfaces whose triangles
   * are no larger than the tetrahedra asked for). When MaximumVolume is also set, the smaller
   * of the two volume bounds applies.
   */
  vtkSetClampMacro(TargetNumberOfCells, vtkIdType, 0, VTK_ID_MAX);
  vtkGetMacro(TargetNumberOfCells, vtkIdType);
  ///@}

  ///@{
  /**
   * Largest volume of any tetrahedron, in the input's units cubed (TetGen's -a); 0 (the
   * default) turns it off. TetGen 1.5.0 leaves a few tetrahedra next to the surface (about 2
   * in 10^4) up to 1.4 times larger.
   */
  vtkSetClampMacro(MaximumVolume, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MaximumVolume, double);
  ///@}

  ///@{
  /**
   * Largest ratio of a tetrahedron's circumradius to its shortest edge (TetGen's -q); 0 turns
   * quality refinement off. Values from 1.1 work in practice, TetGen guarantees termination
   * from 2.0. Default 1.414.
   */
  vtkSetClampMacro(RadiusEdgeRatio, double, 0.0, 100.0);
  vtkGetMacro(RadiusEdgeRatio, double);
  ///@}

  ///@{
  /**
   * Smallest dihedral angle in degrees that quality refinement aims at (TetGen's -q/angle);
   * 0 (the default) keeps TetGen's own default. Only used with RadiusEdgeRatio > 0. Large
   * angles cost many tetrahedra (15 degrees: 28 % more on a sphere of 10^6, 1.7 times the
   * time) and may keep TetGen from terminating; the range is 0..30.
   */
  vtkSetClampMacro(MinimumDihedralAngle, double, 0.0, 30.0);
  vtkGetMacro(MinimumDihedralAngle, double);
  ///@}

  ///@{
  /**
   * Print TetGen's own statistics to standard output. Off by default.
   */
  vtkSetMacro(Verbose, bool);
  vtkGetMacro(Verbose, bool);
  vtkBooleanMacro(Verbose, bool);
  ///@}

  /**
   * The ratio of the volume bound to the mean tetrahedron volume that TargetNumberOfCells
   * assumes: TetGen's tetrahedra are on average this many times smaller than the -a bound
   * (measured on smooth shapes with RadiusEdgeRatio 1.414).
   */
  static double GetMeanVolumeFactor();

  /**
   * The volume enclosed by the last input surface (divergence theorem, absolute value), and
   * the volume bound TetGen was given (0 when none). Valid after a successful update.
   */
  vtkGetMacro(EnclosedVolume, double);
  vtkGetMacro(AppliedMaximumVolume, double);

  /**
   * The TetGen command-line switches the last update used (e.g. "pzQq1.414a0.001").
   */
  const char* GetTetGenSwitches() const;

protected:
  vtkTetGenMesher();
  ~vtkTetGenMesher() override;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  vtkIdType TargetNumberOfCells = 0;
  double MaximumVolume = 0.0;
  double RadiusEdgeRatio = 1.414;
  double MinimumDihedralAngle = 0.0;
  bool Verbose = false;
  double EnclosedVolume = 0.0;
  double AppliedMaximumVolume = 0.0;

private:
  vtkTetGenMesher(const vtkTetGenMesher&) = delete;
  void operator=(const vtkTetGenMesher&) = delete;

  /// The -a bound: MaximumVolume, or the mean volume that TargetNumberOfCells asks, if smaller.
  double ComputeMaximumVolume(double enclosedVolume) const;
  /// Switches: TetGen's switches for the settings and the volume bound.
  void ComposeSwitches(double maximumVolume);

  std::string Switches;
};

#endif
