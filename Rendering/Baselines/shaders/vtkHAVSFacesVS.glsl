//VTK::System::Dec

// HAVS vertex stage: the vertices of the sorted faces to view and clip coordinates.

in vec3 vertexMC;  // model coordinates, shifted and scaled to O(1) on the CPU
in float scalarTF; // scalar in [0, 1]; plus 2 on the vertex copies of boundary faces

uniform mat4 MCVCMatrix; // model -> view, in the same normalized units
uniform mat4 VCDCMatrix; // view -> clip

out vec3 positionVCVSOutput;
out float scalarVSOutput;

void main()
{
  positionVCVSOutput = (MCVCMatrix * vec4(vertexMC, 1.0)).xyz;
  scalarVSOutput = scalarTF;
  gl_Position = VCDCMatrix * vec4(positionVCVSOutput, 1.0);
}
