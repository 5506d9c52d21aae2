// The random numbers of the stochastic mappers (SPT's keep-or-discard thresholds, PBVR's
// thinning of particles), substituted for //Volume::Random::Impl when their shaders are
// assembled.

// PCG-based 4D hash (Jarzynski and Olano, "Hash Functions for GPU Rendering", JCGT 2020).
uvec4 pcg4d(uvec4 v)
{
  v = v * 1664525u + 1013904223u;
  v.x += v.y * v.w;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v.w += v.y * v.z;
  v ^= v >> 16u;
  v.x += v.y * v.w;
  v.y += v.z * v.x;
  v.z += v.x * v.y;
  v.w += v.y * v.z;
  return v;
}
