//VTK::System::Dec
//VTK::Output::Dec

// Adds one pass of the ensemble to the running sum (additive blending is set by the caller),
// and with ENSEMBLE_SECOND_HALF to the second half's sum too (vtkEnsembleBuffer).
// The quad covers the pass exactly, so nearest filtering at texCoord reads one sample.
//Volume::Defines::Dec
in vec2 texCoord;
uniform sampler2D passTexture;

void main()
{
  gl_FragData[0] = texture(passTexture, texCoord);
#ifdef ENSEMBLE_SECOND_HALF
  gl_FragData[1] = gl_FragData[0];
#endif
}
