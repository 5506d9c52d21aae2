/**
 * @file    vtkShaderSourceUtilities.h
 * @brief   small helpers shared by the mappers' shader set-up; not wrapped
 */

#ifndef vtkShaderSourceUtilities_h
#define vtkShaderSourceUtilities_h

#include "vtkMatrix4x4.h"

namespace vtkShaderSourceUtilities
{
/**
 * A vtkMatrix4x4 (row-major, acting on column vectors) as the column-major floats that
 * glUniformMatrix4fv expects without transposition.
 */
inline void ToColumnMajor(vtkMatrix4x4* matrix, float out[16])
{
  for (int column = 0; column < 4; ++column)
  {
    for (int row = 0; row < 4; ++row)
    {
      out[4 * column + row] = static_cast<float>(matrix->GetElement(row, column));
    }
  }
}
}

#endif
