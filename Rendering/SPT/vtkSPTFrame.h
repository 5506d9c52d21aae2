/**
 * @class   vtkSPTFrame
 * @brief   the traversals of one SPT image: one or more volumes into one ensemble
 *
 * Draws the passes of sorting-free projected tetrahedra (vtkSPTVolumeMapper) for a set of
 * volumes, each with its own mesh, pre-integration table and matrices, into one ensemble
 * buffer and one set of depth keys. Everything a pass does is a reduction that ignores order
 * (an atomic minimum of depth keys, then sums), so volumes that interpenetrate composite
 * exactly: their segments interleave per sample as those of one mesh do.
 *
 * A group of repetitions takes two traversals of every volume: the keys (each kept fragment
 * takes the atomic minimum of its depth key per repetition; the first also adds up the exact
 * coverage) and the colors (each fragment adds what it composites in the repetitions where it
 * is visible). The paper's single passes take one traversal per repetition.
 *
 * Its traversals are in vtkSPTFrame.cxx, its programs and their uniforms in
 * vtkSPTFramePrograms.cxx, the choice of what each traversal draws of each volume (points,
 * compute pass, outlines) and of the depth slabs in vtkSPTFrameCells.cxx; the error target's
 * steps are vtkSPTErrorTarget's.
 *
 * Private helper of the SPT module; not wrapped.
 */

#ifndef vtkSPTFrame_h
#define vtkSPTFrame_h

#include "SPTRenderingSPTModule.h" // For export macro

#include "vtkSPTErrorTarget.h" // For the error target's state
#include "vtkType.h"           // For vtkIdType

#include <cstddef>    // For size_t
#include <functional> // For the keys' reduction
#include <string>     // For the shaders' defines
#include <vector>     // For the volumes

class vtkObject;
class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkSPTComputeTraversal;
class vtkSPTDepthKeyBuffer;
class vtkEnsembleBuffer;
class vtkSPTMeshBuffers;
class vtkPreIntegrationTable;
class vtkTextureObject;
struct vtkVolumeViewMatrices;

class SPTRENDERINGSPT_EXPORT vtkSPTFrame
{
public:
  /// One volume of the frame, uploaded and ready to draw.
  struct Volume
  {
    vtkSPTMeshBuffers* Buffers = nullptr;
    vtkPreIntegrationTable* Table = nullptr;
    vtkTextureObject* TableTexture = nullptr;
    const vtkVolumeViewMatrices* Matrices = nullptr;
    double MaxThickness = 0.0; // the table's thickness range, in the mesh's normalized units
    /// Added to the cell ids that the random numbers and depth keys follow, so that they stay
    /// apart across the volumes of a frame.
    unsigned int CellIdOffset = 0;
  };

  /// What a pass writes; see the vtkSPTPass*FS.glsl shaders.
  enum class PassKind
  {
    Single,          // one repetition: the nearest kept segment by the depth test, opaque
    Keys,            // several repetitions: nearest survivors by atomic minimum of depth keys
    KeysAndCoverage, // the same, and every segment's optical depth terms
    Colors,          // several repetitions: what the visible segments (or survivors) add
    Coverage,        // every segment's optical depth terms, for the single passes
    DepthColors,     // one repetition: what the segments not behind the survivor's depth add
    DepthColorsAndCoverage, // the same, and every segment's optical depth terms
  };
  static constexpr int NumberOfPassKinds = 7;

  /// The frame's settings (the mapper's, where several volumes share the frame).
  struct Settings
  {
    /// The visibility estimator, else the survivor estimator (vtkSPTVolumeMapper::Estimator).
    bool VisibilityEstimator = true;
    bool StratifiedSampling = true;
    /// Cells at most this many pixels across on the screen are drawn as points (0: none).
    double SmallCellSize = 0.0;
    int SubpixelLevel = 1;
    unsigned int Seed = 0;
    bool OpaqueScene = false; // opaque geometry was drawn before the volumes
    /// The random numbers follow the meshes' random ids (vtkSPTMeshBuffers), not the indices.
    bool GlobalIds = false;
    /// Draw even one repetition per traversal with depth keys, never the single passes.
    bool AlwaysKeys = false;
    /// Called after each key traversal, before the color traversal reads the keys (the ranks
    /// of a parallel render take their minimum there, and with `slabsDrawn`, the sum of the
    /// depth slabs' optical depths that traversal drew); false stops the frame.
    std::function<bool(vtkSPTDepthKeyBuffer*, bool slabsDrawn)> AfterKeys;
    /// Where set, a group's keys and color traversals visit the cells drawn as points in a compute
    /// pass (vtkSPTComputeTraversal) instead of rasterizing their points.
    vtkSPTComputeTraversal* Compute = nullptr;
    /// With Compute: every cell drawn as a point, rather than only the smallest ones where they
    /// are many.
    bool ComputeEveryPoint = false;
    /// The depth slabs of a group's traversals (1 to 8; see vtkSPTVolumeMapper::SetDepthSlabs()).
    /// Their optical depths are drawn with the coverage, before any color traversal of the image.
    int DepthSlabs = 1;
  };
  static constexpr int MaximumDepthSlabs = 8;

  vtkSPTFrame(vtkOpenGLRenderWindow* window, vtkEnsembleBuffer* ensemble,
    vtkSPTDepthKeyBuffer* depthKeys, const std::vector<Volume>& volumes, const Settings& settings,
    vtkObject* reporter);
  virtual ~vtkSPTFrame() = default;

  /**
   * Draw repetitions [first, first + count) into the ensemble's sum, perPass per traversal;
   * with halves, the second half of them also into the second half's sum, each half a block
   * of strata of its own. With coverage, the exact coverage is drawn too. False, after an
   * error on the reporter, when a shader or a buffer fails.
   */
  virtual bool DrawRepetitions(
    int first, int count, int perPass, bool coverage, bool halves = false);

  /// Draw at most count repetitions from first on, in rounds of two halves of equal size,
  /// until the noise estimated from the halves is at most target. Returns how many were drawn,
  /// or -1 on failure. `exactCoverage`: the coverage is (or is being) drawn for this image.
  int DrawToTarget(int first, int count, int perPass, bool coverage, bool exactCoverage,
    double target, vtkSPTErrorTarget::State& state);

  /// Whether every part of the frame was drawn: `drawn`, in one process.
  virtual bool Finish(bool drawn) { return drawn; }

  /// The depth slabs this frame draws (Settings::DepthSlabs, clamped).
  int GetDepthSlabs() const { return this->FrameSettings.DepthSlabs; }

  /// How many tetrahedra of a volume the traversals draw as points, and how many of those a
  /// traversal of this frame visited in a compute pass (Settings::Compute).
  vtkIdType GetPointCellCount(size_t volume) const { return this->PointCellCounts[volume]; }
  vtkIdType GetComputedCellCount(size_t volume) const { return this->ComputedCellCounts[volume]; }

protected:
  /// DrawToTarget()'s estimate, once the halves hold `halfCount` repetitions each: the noise
  /// of the image's largest tile and of its median tile; the repetitions that follow are drawn
  /// into the tiles still above `target`. False on failure.
  virtual bool EstimateNoise(
    int halfCount, bool exactCoverage, double target, double& estimate, double& median);

private:
  // The image units of the frame's images (depth keys, the compute traversal's fixed-point
  // sums, the depth slabs' sums and then their controls).
  enum ImageUnit
  {
    DepthKeyImageUnit = 0,
    SumsImageUnit = 1,
    SlabDepthsImageUnit = 2
  };

  // The programs and their uniforms (vtkSPTFramePrograms.cxx).
  vtkShaderProgram* ReadyProgram(bool cellScalars, bool clippedCells, bool points, PassKind kind,
    int passRepetitions, bool halves);
  // The compute traversal's program of a keys or colors pass kind (vtkSPTTetrahedraCS.glsl).
  vtkShaderProgram* ReadyComputeProgram(
    bool cellScalars, PassKind kind, int passRepetitions, bool halves);
  // Whether a traversal of this kind visits the volume's points in a compute pass.
  bool Computes(PassKind kind, size_t volume) const;
  // Whether a traversal of this kind visits some volume's points in a compute pass.
  bool Computes(PassKind kind) const;
  // Whether a group's traversals visit at least half of the frame's cells in a compute pass.
  bool ComputesMostCells() const;
  // Compile the programs of the pass kinds needed, for the volumes' kinds of scalars. Where a
  // compute program does not build, the rasterizer takes its cells.
  bool ReadyPrograms(const bool (&needed)[NumberOfPassKinds], int passRepetitions, int first,
    int count, bool halves);
  // One traversal of every volume with the program of that pass kind.
  void Traverse(PassKind kind, int repetition, int inGroup);
  enum class Primitive;
  // The part of the traversal that draws the volume's cells of one primitive.
  void TraversePrimitive(PassKind kind, size_t v, Primitive primitive, int repetition, int inGroup);
  // The volume's smallest cells in a compute pass with the bound program.
  void DispatchComputed(vtkShaderProgram* program, PassKind kind, size_t v);
  // Traverse(), for a pass that `adds` into the bound targets (the second too with
  // `secondTarget`): a compute traversal adds its fixed-point sums there after it. False if
  // its sums cannot be allocated or added.
  bool TraverseAdding(PassKind kind, int repetition, int inGroup, bool adds, bool secondTarget);
  // Draw the volume's tetrahedra [firstPoint, pointCells) as points, or those from pointCells
  // on as triangles.
  void DrawTetrahedra(const Volume& volume, vtkShaderProgram* program, bool points,
    vtkIdType firstPoint, vtkIdType pointCells);
  bool DrawSingles(int first, int count, bool coverage, bool halves);
  bool DrawGroups(int first, int count, int perPass, bool coverage, bool halves);
  // A group's key traversal, from repetition r (with the coverage, and then the slabs' mean
  // color, where `withCoverage`); its keys then reduced by Settings::AfterKeys.
  bool DrawGroupKeys(int r, int inGroup, bool withCoverage);
  // A group's color traversal, against its survivors; the repetitions from `secondHalfFrom`
  // in the group on add to the second half's sum too, with `halves`.
  bool DrawGroupColors(int r, int inGroup, int secondHalfFrom, bool halves);
  // The visibility estimator one repetition per traversal pair: the single pass's depth test
  // finds each survivor, and the color traversal (with the coverage, in the first) reads its
  // depth.
  bool DrawDepthSurvivors(int first, int count, bool coverage);
  // Between a group's keys and colors: sort each half's keys for the visibility estimator,
  // and write the farthest survivor into the depth buffer and test the color traversal
  // against it, so that fragments behind all the survivors are not shaded. `culled` is false
  // (and no depth test) where the frame cannot cull. False if the keys needed sorting and
  // could not be sorted: the color traversal would count the survivors wrongly.
  bool PrepareSurvivors(int inGroup, int secondHalfFrom, bool& culled);
  void SetFrameUniforms(vtkShaderProgram* program, int first, int count, bool halves) const;
  // After the image's coverage and slab sums: the coverage's color becomes the slabs' mean
  // color times its optical depth (vtkSPTSlabsMeanFS.glsl). False if its shader fails.
  bool WriteSlabsMeanColor();
  // The defines of a pass kind's depth slabs; empty for one slab or a kind without them.
  std::string SlabDefines(PassKind kind) const;
  // The defines of a pass kind's shaders, for cells with scalars per cell or per point.
  std::string PassDefines(PassKind kind, bool cellScalars, int passRepetitions, bool halves) const;
  // Split the depth range of the volumes' bounds, as the camera sees it, into equal slabs.
  void ChooseSlabs();
  // The window depths where slabs 1 to 7 start, and 2 where none does (two vec4 uniforms).
  float SlabStarts[MaximumDepthSlabs] = { 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f, 2.0f };
  static void SetVolumeUniforms(vtkShaderProgram* program, const Volume& volume);

  vtkOpenGLRenderWindow* Window;
  vtkEnsembleBuffer* Ensemble;
  vtkSPTDepthKeyBuffer* DepthKeys;
  const std::vector<Volume>& Volumes;
  Settings FrameSettings;
  vtkObject* Reporter;
  bool NearPlaneCuts = false; // the near plane cuts the bounds of some volume
  // The samples of the pass that the volumes' bounds cover on the screen (x, y, width,
  // height), with a sample of margin; the whole pass where the near plane cuts them or the
  // ranks of a parallel frame combine the keys. A group's keys are cleared, sorted and read
  // only there: no fragment lands outside it.
  int Footprint[4] = { 0, 0, 0, 0 };
  void ChooseFootprint();
  bool ClippingPlanes = false; // some volume has clipping planes (vtkVolumeViewMatrices)
  // Per volume: its leading tetrahedra drawn as one point each, whose fragments clip their
  // rays by the cell's face planes (vtkSPTTetrahedraPointsVS.glsl), the classes of size of
  // vtkSPTMeshBuffers about SmallCellSize pixels across or less; the others are drawn as the
  // outline of their projection (vtkSPTTetrahedraGS.glsl). Two ranges: each cell is drawn
  // exactly once.
  std::vector<vtkIdType> PointCellCounts;
  // Per volume: the leading ones of the cells drawn as points that a group's keys and color
  // traversals visit in a compute pass instead (Settings::Compute); they are rasterized as
  // points in the other traversals.
  std::vector<vtkIdType> ComputeCellCounts;
  std::vector<vtkIdType> ComputedCellCounts; // per volume: by a compute pass, in this frame
  void ChooseSmallCells();
  // Whether a traversal of the kind rasterizes cells of the volume as points (or triangles),
  // and the first cell it rasterizes as a point.
  bool Rasterizes(PassKind kind, size_t volume, bool points) const;
  vtkIdType FirstRasterizedPoint(PassKind kind, size_t volume) const;
  enum class Primitive
  {
    Computed, // the smallest cells, in a compute pass
    Points,   // the small cells, one point each
    Outlines, // the others, the outline of their projection
  };
  // The programs of this frame, by pass kind, by scalars per point (0) or per cell (1), and by
  // primitive: the projection's outline (0) or one point per tetrahedron (1).
  vtkShaderProgram* Programs[NumberOfPassKinds][2][2] = {};
  // The compute traversal's programs, by pass kind and scalars (Settings::Compute).
  vtkShaderProgram* ComputePrograms[NumberOfPassKinds][2] = {};
  vtkShaderProgram*& ProgramOf(PassKind kind, size_t volume, bool points);
};

#endif
