// The particle clouds' pure functions (seed 003; issue 22), shared by the shaders that draw
// particles and by the CPU lighting (src/particles), so both see the same particle.
#ifndef NEPHELE_PARTICLE_INC
#define NEPHELE_PARTICLE_INC

// A particle's opacity profile at squared distance q2 = (d / radius)^2 from its centre:
// (1 - q2)^2 inside, 0 outside; smooth at the rim, 1 at the centre.
float particle_profile(float q2) {
  float t = max(1.0f - q2, 0.0f);
  return t * t;
}

#endif
