/**
 * @class   vtkSITetrahedralVolumeRepresentationProxy
 * @brief   server-side proxy of vtkTetrahedralVolumeRepresentation: gives it its mapper subproxy
 *
 * The server manager creates the subproxies of a representation proxy on every process, but
 * has no XML for "use this subproxy's object as my mapper". This class adds that: after the
 * objects are created, the object of the subproxy named "VolumeMapper" becomes the
 * representation's mapper (vtkTetrahedralVolumeRepresentation::SetVolumeMapper()). A new mapper
 * therefore needs only XML: a mapper proxy, and a representation proxy with this si_class and
 * a "VolumeMapper" subproxy.
 *
 * The superclass registers ParaView's own unstructured-grid mappers as before.
 *
 * @sa
 * vtkTetrahedralVolumeRepresentation vtkSIUnstructuredGridVolumeRepresentationProxy
 */

#ifndef vtkSITetrahedralVolumeRepresentationProxy_h
#define vtkSITetrahedralVolumeRepresentationProxy_h

#include "SPTParaViewRepresentationModule.h" // For export macro
#include "vtkSIUnstructuredGridVolumeRepresentationProxy.h"

class SPTPARAVIEWREPRESENTATION_EXPORT vtkSITetrahedralVolumeRepresentationProxy
  : public vtkSIUnstructuredGridVolumeRepresentationProxy
{
public:
  static vtkSITetrahedralVolumeRepresentationProxy* New();
  vtkTypeMacro(
    vtkSITetrahedralVolumeRepresentationProxy, vtkSIUnstructuredGridVolumeRepresentationProxy);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkSITetrahedralVolumeRepresentationProxy();
  ~vtkSITetrahedralVolumeRepresentationProxy() override;

  /**
   * Create the objects, then give the representation its "VolumeMapper" subproxy's object.
   */
  bool CreateVTKObjects() override;

private:
  vtkSITetrahedralVolumeRepresentationProxy(
    const vtkSITetrahedralVolumeRepresentationProxy&) = delete;
  void operator=(const vtkSITetrahedralVolumeRepresentationProxy&) = delete;
};

#endif
