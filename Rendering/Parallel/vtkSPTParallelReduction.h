/**
 * @class   vtkSPTParallelReduction
 * @brief   the reductions that combine the ranks' pieces of one SPT image
 *
 * Every step of an SPT frame is a reduction that ignores order, so ranks that each draw their
 * own piece of a data set (any shape, interleaved, with overlapping bounds) combine into the
 * image of the whole without redistributing cells or compositing in visibility order:
 * - the scene depth (opaque geometry) by a global minimum, so that every rank's volume is
 *   hidden by every rank's geometry;
 * - after each key traversal, the depth keys (per sample and repetition) by a global minimum,
 *   so that every rank's color traversal tests against the survivors of all pieces;
 * - the sums of colors and of coverage by a global sum, to the rank that resolves (0);
 * - with an error target, after each step of repetitions, the sums of the two halves to rank
 *   0, whose noise estimate every rank then follows.
 *
 * Before any of this, Agree() exchanges one small record per rank (settings, scalars, bounds)
 * so that every rank takes part in the same collective calls or none does: ranks that differ
 * give one error naming the rank and the difference, and nothing is drawn (never a hang).
 *
 * Private helper of the SPT module; not wrapped.
 */

#ifndef vtkSPTParallelReduction_h
#define vtkSPTParallelReduction_h

#include "SPTRenderingParallelModule.h" // For export macro
#include "vtkObject.h"

#include <string>  // For the errors
#include <utility> // For the settings
#include <vector>  // For the settings

class vtkMultiProcessController;
class vtkPreIntegrationTable;
class vtkSPTDepthKeyBuffer;
class vtkTextureObject;

class SPTRENDERINGPARALLEL_EXPORT vtkSPTParallelReduction : public vtkObject
{
public:
  static vtkSPTParallelReduction* New();
  vtkTypeMacro(vtkSPTParallelReduction, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The processes to combine; null: none (nothing is reduced).
  void SetController(vtkMultiProcessController* controller);
  vtkMultiProcessController* GetController() const { return this->Controller; }

  /// What one rank brings to a frame.
  struct Piece
  {
    bool Ready = true;       // the rank could prepare its part (window, input, table)
    bool EmptyImage = false; // its viewport has no pixels: nothing to draw, not an error
    bool HasCells = false;   // its piece has tetrahedra to draw
    std::string ArrayName;   // the scalars selected (pieces with cells only)
    int Components = 0;
    bool CellScalars = false;
    bool GlobalIds = false;   // the piece has global cell ids
    bool OpaqueScene = false; // opaque geometry was drawn before the volume on this rank
    double Bounds[6] = { 0.0, -1.0, 0.0, -1.0, 0.0, -1.0 }; // finite points; min > max: none
    double ScalarRange[2] = { 0.0, -1.0 };
    double MaxEdgeLength = 0.0; // data units
    double Tetrahedra = 0.0;    // in the piece
  };

  /// What the ranks agreed on.
  struct Agreement
  {
    bool AnyCells = false;
    bool GlobalIds = false;
    bool OpaqueScene = false;
    double Bounds[6] = { 0.0, 0.0, 0.0, 0.0, 0.0, 0.0 };
    double ScalarRange[2] = { 0.0, 0.0 };
    double MaxEdgeLength = 0.0;
    double Tetrahedra = 0.0; // of all pieces
  };

  /// Named values that must be equal on every rank (sampling settings, image size, ...).
  using Settings = std::vector<std::pair<std::string, double>>;

  /**
   * Exchange every rank's settings and piece. True when they agree, with the union of the
   * pieces in `agreement`; else false on every rank, with the same reason in `error` (the
   * first rank that differs, and how), which is empty when the ranks agree on an image with
   * no pixels. A collective call.
   */
  bool Agree(
    const Settings& settings, const Piece& piece, Agreement& agreement, std::string& error);

  /**
   * The opaque scene of all ranks, composited as a z-buffer compositor does: the global
   * minimum of the scene depth texture, written back on every rank, and on rank 0 the color
   * of the rank nearest at each pixel (the lowest rank where several are at one depth).
   * `color` holds this rank's RGBA bytes, one pixel per texel of `depth`, and on return rank
   * 0's holds the composited color. Collective.
   */
  bool CompositeScene(vtkTextureObject* depth, std::vector<unsigned char>& color);

  ///@{
  /// The global minimum of the depth keys, and the sum of the depth slabs' optical depths
  /// (fixed point, the same in any order), on every rank. Null `keys`: this rank's part of a
  /// reduction it could not draw, `missed` keys of "nothing kept" or sums of zero. Collective.
  bool ReduceKeys(vtkSPTDepthKeyBuffer* keys, size_t missed = 0);
  bool ReduceSlabs(vtkSPTDepthKeyBuffer* keys, size_t missed = 0);
  ///@}

  /// Move float RGBA textures of `texels` texels each to rank 0: rank 0's hold the global sums,
  /// the others' are cleared, so that what any rank adds later is added once when they move
  /// again. A texture of another size (not allocated after a failure) adds zeros. Collective.
  bool ReduceSums(const std::vector<vtkTextureObject*>& textures, size_t texels);

  /**
   * Integrate a prepared pre-integration table across the ranks (see
   * vtkPreIntegrationTable::Prepare(); `prepared` says whether this rank's Prepare() succeeded,
   * `pending` whether its table must be integrated again): where every rank prepared the
   * same samples and some rank's table is pending, each integrates an equal share of the
   * scalar pairs and every rank receives all of them. False on every rank, with the first rank
   * whose transfer function differs from rank 0's in `error`, when they differ. Where a rank
   * could not prepare, nothing is shared: each integrates its own and reports its own error.
   * Collective.
   */
  bool ShareTable(vtkPreIntegrationTable* table, bool prepared, bool pending, std::string& error);

  /// The minimum of each of `count` values over the ranks, on every rank. Collective.
  bool AllMinimum(int* values, int count);

  /// Whether `ok` holds on every rank, and rank 0's `values` on every rank (the others' are
  /// ignored): the noise of each tile of the image. Collective.
  bool ShareTileNoise(bool ok, std::vector<double>& values);

  /// Whether `ok` holds on every rank. Collective.
  bool AllSucceeded(bool ok);

  ///@{
  /// The bytes this rank contributed to the reductions since the last ResetBytes() (what it
  /// sends once into a tree or ring reduction; MPI moves about that much per rank).
  void ResetBytes() { this->Bytes = 0; }
  size_t GetBytes() const { return this->Bytes; }
  ///@}

protected:
  vtkSPTParallelReduction();
  ~vtkSPTParallelReduction() override;

private:
  vtkSPTParallelReduction(const vtkSPTParallelReduction&) = delete;
  void operator=(const vtkSPTParallelReduction&) = delete;

  // Why the gathered records disagree, or an empty string.
  static std::string Compare(const Settings& settings, const std::vector<double>& records,
    const std::vector<char>& names, int ranks);

  vtkMultiProcessController* Controller = nullptr;
  size_t Bytes = 0;
  // The element-wise reduction over the ranks of the words that `read` reads from `keys`,
  // written back with `write`, on every rank; null `keys`: `missed` words of `identity`.
  using ReadWords = std::vector<unsigned int> (vtkSPTDepthKeyBuffer::*)();
  using WriteWords = void (vtkSPTDepthKeyBuffer::*)(const std::vector<unsigned int>&);
  bool ReduceWords(vtkSPTDepthKeyBuffer* keys, ReadWords read, WriteWords write, size_t missed,
    unsigned int identity, int operation);
};

#endif
