//VTK::System::Dec
//VTK::Output::Dec

// Adds one pass of the ensemble to the running sum (additive blending is set by the caller).
// The quad covers the pass exactly, so nearest filtering at texCoord reads one sample.
in vec2 texCoord;
uniform sampler2D passTexture;

void main()
{
  gl_FragData[0] = texture(passTexture, texCoord);
}
