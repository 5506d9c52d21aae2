//VTK::System::Dec

// SPT vertex stage: points to (normalized) view coordinates (the geometry stage makes the clip
// coordinates); the geometry stage needs
// all four vertices of a tetrahedron to classify its projection.

in vec3 vertexMC;    // model coordinates, shifted and scaled to O(1) on the CPU
in float scalarTF;   // scalar mapped to [0, 1] over the pre-integration table's range

uniform mat4 MCVCMatrix; // model -> view, in the same normalized units

out vec3 positionVCVSOutput;
out float scalarVSOutput;

void main()
{
  positionVCVSOutput = (MCVCMatrix * vec4(vertexMC, 1.0)).xyz;
  scalarVSOutput = scalarTF;
}
