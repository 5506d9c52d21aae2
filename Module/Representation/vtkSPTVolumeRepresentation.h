/**
 * @class   vtkSPTVolumeRepresentation
 * @brief   ParaView's unstructured-grid volume representation, drawn by one of this project's
 * mappers
 *
 * The representation types that the SPT plugin adds to ParaView ("Volume (SPT)", and one per
 * further mapper) are each a proxy of this class whose subproxy "VolumeMapper" is the mapper
 * that draws it (vtkSPTVolumeMapper, ...). vtkSISPTVolumeRepresentationProxy hands that mapper
 * over with SetVolumeMapper() on every process.
 *
 * Everything else is vtkUnstructuredGridVolumeRepresentation's: the split into tetrahedra, the
 * translucent-surface LOD, and, under MPI, the request for ordered compositing, for which
 * vtkPVRenderView redistributes the data into spatially disjoint pieces and composites the
 * pieces' premultiplied images in visibility order. That suits every mapper that renders its
 * own piece as a premultiplied image over a transparent background, as SPT does.
 *
 * The inherited volume-mapper selection (SetActiveVolumeMapper(), the "SelectMapper" property
 * of ParaView's "Volume" representation) is ignored: this representation always draws with its
 * own mapper.
 *
 * @sa
 * vtkUnstructuredGridVolumeRepresentation vtkSISPTVolumeRepresentationProxy vtkSPTVolumeMapper
 */

#ifndef vtkSPTVolumeRepresentation_h
#define vtkSPTVolumeRepresentation_h

#include "SPTParaViewRepresentationModule.h" // For export macro
#include "vtkSmartPointer.h"                 // For the mapper
#include "vtkUnstructuredGridVolumeRepresentation.h"

class vtkAbstractVolumeMapper;

class SPTPARAVIEWREPRESENTATION_EXPORT vtkSPTVolumeRepresentation
  : public vtkUnstructuredGridVolumeRepresentation
{
public:
  static vtkSPTVolumeRepresentation* New();
  vtkTypeMacro(vtkSPTVolumeRepresentation, vtkUnstructuredGridVolumeRepresentation);
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

protected:
  vtkSPTVolumeRepresentation();
  ~vtkSPTVolumeRepresentation() override;

  /**
   * The superclass's array and scalar-mode forwarding, plus the color map's vector mode
   * (magnitude or one component) for the mappers that have one.
   */
  void UpdateMapperParameters() override;

private:
  vtkSPTVolumeRepresentation(const vtkSPTVolumeRepresentation&) = delete;
  void operator=(const vtkSPTVolumeRepresentation&) = delete;

  vtkSmartPointer<vtkAbstractVolumeMapper> VolumeMapper;
};

#endif
