/**
 * @class   vtkSISPTVolumeRepresentationProxy
 * @brief   server-side proxy of vtkSPTVolumeRepresentation: gives it its mapper subproxy
 *
 * The server manager creates the subproxies of a representation proxy on every process, but
 * has no XML for "use this subproxy's object as my mapper". This class adds that: after the
 * objects are created, the object of the subproxy named "VolumeMapper" becomes the
 * representation's mapper (vtkSPTVolumeRepresentation::SetVolumeMapper()). A new mapper
 * therefore needs only XML: a mapper proxy, and a representation proxy with this si_class and
 * a "VolumeMapper" subproxy.
 *
 * The superclass registers ParaView's own unstructured-grid mappers as before.
 *
 * @sa
 * vtkSPTVolumeRepresentation vtkSIUnstructuredGridVolumeRepresentationProxy
 */

#ifndef vtkSISPTVolumeRepresentationProxy_h
#define vtkSISPTVolumeRepresentationProxy_h

#include "SPTParaViewRepresentationModule.h" // For export macro
#include "vtkSIUnstructuredGridVolumeRepresentationProxy.h"

class SPTPARAVIEWREPRESENTATION_EXPORT vtkSISPTVolumeRepresentationProxy
  : public vtkSIUnstructuredGridVolumeRepresentationProxy
{
public:
  static vtkSISPTVolumeRepresentationProxy* New();
  vtkTypeMacro(vtkSISPTVolumeRepresentationProxy, vtkSIUnstructuredGridVolumeRepresentationProxy);
  void PrintSelf(ostream& os, vtkIndent indent) override;

protected:
  vtkSISPTVolumeRepresentationProxy();
  ~vtkSISPTVolumeRepresentationProxy() override;

  /**
   * Create the objects, then give the representation its "VolumeMapper" subproxy's object.
   */
  bool CreateVTKObjects() override;

private:
  vtkSISPTVolumeRepresentationProxy(const vtkSISPTVolumeRepresentationProxy&) = delete;
  void operator=(const vtkSISPTVolumeRepresentationProxy&) = delete;
};

#endif
