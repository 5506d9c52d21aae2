/**
 * @class   vtkPreIntegrationTable
 * @brief   pre-integrated color and opacity of linear ray segments, as a 3D texture
 *
 * The table holds, for a ray segment whose scalar varies linearly from a front value to a back
 * value over a given length, the premultiplied color and the opacity of that segment
 * (Roettger, Kraus and Ertl 2000; Engel, Kraus and Ertl 2001). Axes: front scalar, back scalar,
 * and the square root of the length (finer where short segments, the common case, change
 * fastest).
 *
 * The optical model is the one of VTK's vtkUnstructuredGridLinearRayIntegrator, the reference
 * of this project: the attenuation coefficient is tau(s) = opacity(s) / unit distance, and the
 * emitted light is C(s) tau(s) (Moreland and Angel 2004), so a homogeneous segment of length d
 * has alpha = 1 - exp(-tau d) and premultiplied color C alpha.
 *
 * Private helper of SPT::RenderingCore, shared by the mappers; not wrapped.
 */

#ifndef vtkPreIntegrationTable_h
#define vtkPreIntegrationTable_h

#include "SPTRenderingCoreModule.h" // For export macro
#include "vtkNew.h"                 // For the texture
#include "vtkObject.h"
#include "vtkTimeStamp.h"               // For the build time
#include "vtkTransferFunctionSamples.h" // For the samples

#include <cstdint> // For the signature
#include <string>  // For the error
#include <vector>  // For the table

class vtkOpenGLRenderWindow;
class vtkShaderProgram;
class vtkTextureObject;
class vtkVolumeProperty;
class vtkWindow;

class SPTRENDERINGCORE_EXPORT vtkPreIntegrationTable : public vtkObject
{
public:
  static vtkPreIntegrationTable* New();
  vtkTypeMacro(vtkPreIntegrationTable, vtkObject);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /**
   * Build the table for the first component of the property's transfer functions, over the
   * scalar range and for lengths from 0 to maxLength (data units). Rebuilds only when one of
   * these, or the property, changed since the last build. Returns false when the property
   * cannot be integrated (unit distance not positive); GetLastError() says why, for the
   * caller to report.
   */
  bool Update(vtkVolumeProperty* property, const double scalarRange[2], double maxLength,
    int scalarResolution, int lengthResolution);
  const std::string& GetLastError() const { return this->LastError; }

  ///@{
  /**
   * Update() in steps, for callers that share the integration (the ranks of a parallel render
   * each integrate a part of the scalar pairs). Prepare() samples the functions for these
   * axes and says whether the table must be integrated again (`pending`; false with
   * GetLastError() as Update()). Then IntegrateScalarPairs() integrates the pairs
   * [first, last) of GetNumberOfScalarPairs() (front scalar fastest) into `out`, each pair's
   * GetValuesPerScalarPair() floats after the last's (its lengths, RGBA), and SetIntegrated()
   * takes every pair's values, in that layout. Update() does all three.
   */
  bool Prepare(vtkVolumeProperty* property, const double scalarRange[2], double maxLength,
    int scalarResolution, int lengthResolution, bool& pending);
  vtkIdType GetNumberOfScalarPairs() const;
  int GetValuesPerScalarPair() const { return 4 * this->LengthResolution; }
  void IntegrateScalarPairs(vtkIdType first, vtkIdType last, float* out) const;
  void SetIntegrated(const float* pairs);
  ///@}

  /**
   * A digest of what the last Prepare() or Update() sampled, and of the axes: tables with
   * equal signatures integrate to the same values.
   */
  std::uint64_t GetSignature() const;

  /// When the contents of the table last changed.
  vtkMTimeType GetBuildTime() const { return this->BuildTime.GetMTime(); }

  /// How many times the table was integrated (the costly part of Update()); for tests.
  int GetIntegrationCount() const { return this->IntegrationCount; }

  ///@{
  /// Table layout: RGBA floats, front scalar fastest, then back scalar, then length.
  int GetScalarResolution() const { return this->ScalarResolution; }
  int GetLengthResolution() const { return this->LengthResolution; }
  const std::vector<float>& GetTable() const { return this->Table; }
  ///@}

  ///@{
  /// The scalar and the length that sample (i, j or k) of the table stands for.
  double GetScalar(int i) const;
  double GetLength(int k) const;
  ///@}

  /**
   * The table as a trilinearly filtered 3D texture of the given context, uploaded when the
   * table changed since the last upload.
   */
  vtkTextureObject* GetTexture(vtkOpenGLRenderWindow* renWin);

  /**
   * Set the uniforms through which the shaders read the table: `preIntegrationTable` (the
   * texture's unit: activate it first), `tableTexelScale` and `tableTexelOffset` (from [0, 1]
   * to the centers of the first and last texels) and `thicknessToTable` (1 / the longest
   * thickness, in the units of the shaders' lengths: `maxThickness`).
   */
  void SetUniforms(vtkShaderProgram* program, vtkTextureObject* texture, double maxThickness) const;

  /// Bytes held on the GPU.
  size_t GetGPUMemorySize() const;

  void ReleaseGraphicsResources(vtkWindow* window);

protected:
  vtkPreIntegrationTable();
  ~vtkPreIntegrationTable() override;

private:
  vtkPreIntegrationTable(const vtkPreIntegrationTable&) = delete;
  void operator=(const vtkPreIntegrationTable&) = delete;

  // False, with LastError naming the settings, for a table too large to integrate.
  bool CheckSize(int scalarResolution, int lengthResolution);
  // Whether the table has these axes.
  bool HasAxes(const double scalarRange[2], double maxLength, int scalarResolution,
    int lengthResolution) const;
  // Pairs [first, last) in parallel, pair p's lengths from out + (p - first) * pairStride.
  void IntegrateScalarPairs(vtkIdType first, vtkIdType last, float* out, vtkIdType pairStride,
    vtkIdType lengthStride) const;
  // One scalar pair's lengths, the k-th at out + k * stride.
  void IntegrateScalarPair(int front, int back, float* out, vtkIdType stride) const;
  // The attenuation (`tau`) and color at the middle of each step from scalar front to back.
  void SampleSteps(int front, int back, std::vector<double>& tau, std::vector<double>& color) const;
  // Lengths in pairs, even then odd, each pair's color sums and transmittances side by side:
  // the even and the odd lengths' products are two chains that do not wait for each other.
  struct LengthPair
  {
    double Red[2] = { 0.0, 0.0 };
    double Green[2] = { 0.0, 0.0 };
    double Blue[2] = { 0.0, 0.0 };
    double Transmittance[2] = { 1.0, 1.0 };
  };
  // The steps' compositing front to back for every length at once, into `pairs`;
  // `perUnitDepth` turns a step's attenuation into the optical depth c_m of length 1.
  static void IntegrateLengths(const std::vector<double>& tau, const std::vector<double>& color,
    double perUnitDepth, int lengths, std::vector<LengthPair>& pairs);
  // Takes the integrated table (texture layout; swapped in when it differs) as the pending
  // axes' and samples'.
  void Commit(std::vector<float>& table);

  int ScalarResolution = 0;
  int LengthResolution = 0;
  double ScalarRange[2] = { 0.0, 0.0 };
  double MaxLength = 0.0;

  // Color and attenuation (opacity / unit distance) sampled finely over the scalar range, and
  // when those the table holds changed last.
  vtkTransferFunctionSamples Samples;
  vtkMTimeType IntegratedSamples = 0;
  // Prepared but not integrated yet: the axes above are the pending ones.
  bool Pending = false;
  vtkVolumeProperty* PendingProperty = nullptr; // identity only
  vtkMTimeType PendingSamples = 0;

  std::vector<float> Table;
  std::string LastError;
  vtkVolumeProperty* LastProperty = nullptr; // identity only, never dereferenced
  vtkTimeStamp CheckTime;                    // the inputs were last compared
  int IntegrationCount = 0;
  vtkTimeStamp BuildTime; // the contents last changed
  vtkTimeStamp UploadTime;
  vtkNew<vtkTextureObject> Texture;
};

#endif
