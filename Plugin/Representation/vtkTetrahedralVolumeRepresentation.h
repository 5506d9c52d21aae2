/**
 * @class   vtkTetrahedralVolumeRepresentation
 * @brief   ParaView's unstructured-grid volume representation, drawn by one of this project's
 * tetrahedral mappers
 *
 * One class for every representation type that the SPT plugin adds to ParaView ("Volume
 * (SPT)", "Volume (HAVS-like)", "Volume (PBVR)"): each type is a proxy of this class whose
 * subproxy "VolumeMapper" is the mapper that draws it, a vtkTetrahedralVolumeMapper
 * (vtkPSPTVolumeMapper, vtkHAVSVolumeMapper, vtkPBVRVolumeMapper). The subproxy's XML
 * command hands that mapper over with SetVolumeMapper() on every process.
 *
 * Everything else is vtkUnstructuredGridVolumeRepresentation's: the split into tetrahedra, the
 * translucent-surface LOD, and, under MPI, the request for ordered compositing, for which
 * vtkPVRenderView redistributes the data into spatially disjoint pieces and composites the
 * pieces' premultiplied images in visibility order. The sorted mappers (HAVS-like) and PBVR
 * keep that.
 *
 * SPT (vtkPSPTVolumeMapper) needs neither: under MPI with distributed rendering, this
 * representation asks for no redistribution and no ordered compositing, and hands the mapper the
 * processes' controller, so that each rank draws its own piece as it is and the ranks combine by
 * reductions; rank 0 resolves the image and marks its pixels in the depth buffer, and IceT's
 * depth compositing keeps them.
 *
 * The inherited volume-mapper selection (SetActiveVolumeMapper(), the "SelectMapper" property
 * of ParaView's "Volume" representation) is ignored: this representation always draws with its
 * own mapper.
 *
 * @sa
 * vtkUnstructuredGridVolumeRepresentation vtkTetrahedralVolumeMapper vtkPSPTVolumeMapper
 */

#ifndef vtkTetrahedralVolumeRepresentation_h
#define vtkTetrahedralVolumeRepresentation_h

#include "SPTParaViewRepresentationModule.h" // For export macro
#include "vtkSmartPointer.h"                 // For the mapper
#include "vtkUnstructuredGridVolumeRepresentation.h"

class vtkAbstractVolumeMapper;
class vtkMultiProcessController;
class vtkSPTVolumeMapper;

class SPTPARAVIEWREPRESENTATION_EXPORT vtkTetrahedralVolumeRepresentation
  : public vtkUnstructuredGridVolumeRepresentation
{
public:
  static vtkTetrahedralVolumeRepresentation* New();
  vtkTypeMacro(vtkTetrahedralVolumeRepresentation, vtkUnstructuredGridVolumeRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The mapper that draws this representation, set once when the proxy is created.
   * Default none (VTK's projected tetrahedra draw until it is set).
   */
  void SetVolumeMapper(vtkAbstractVolumeMapper* mapper);
  vtkAbstractVolumeMapper* GetVolumeMapper();
  ///@}

  /**
   * Ignored: the representation always draws with the mapper given to SetVolumeMapper().
   */
  void SetActiveVolumeMapper(const char* name) override;

  /**
   * The superclass's requests, except for vtkSPTVolumeMapper under MPI: no redistribution and
   * no ordered compositing, and the mapper's controller set for distributed renders.
   */
  int ProcessViewRequest(
    vtkInformationRequestKey* request, vtkInformation* inInfo, vtkInformation* outInfo) override;

protected:
  vtkTetrahedralVolumeRepresentation();
  ~vtkTetrahedralVolumeRepresentation() override;

  /**
   * The superclass's array and scalar-mode forwarding, plus the color map's vector mode
   * (magnitude or one component) for the mappers that have one.
   */
  void UpdateMapperParameters() override;

private:
  vtkTetrahedralVolumeRepresentation(const vtkTetrahedralVolumeRepresentation&) = delete;
  void operator=(const vtkTetrahedralVolumeRepresentation&) = delete;

  // The processes SPT combines across, or null when it draws alone.
  vtkMultiProcessController* ParallelController();
  // A piece without the selected array replaced by an empty grid with it, so that the
  // mapper is still called and takes part in the reductions.
  static void KeepPieceDrawn(vtkSPTVolumeMapper* mapper, vtkMultiProcessController* controller);

  vtkSmartPointer<vtkAbstractVolumeMapper> VolumeMapper;
};

#endif
