// SPDX-License-Identifier: BSD-3-Clause
// Phong shading and opacity correction, as render/render_model.h states them.

uniform float uUnit;             // smallest voxel spacing: the length TF opacities refer to
uniform vec3 uToLight;           // world, unit
uniform vec4 uPhong;             // ambient, diffuse, specular, shininess
uniform bool uShadingEnabled;
uniform float uStopTransmittance;  // 1 - termination alpha: rays stop at or below this
uniform float uShadowStop;         // shadow rays stop below this transmittance
uniform float uStep;               // trilinear step, world units

// Specialisations the renderer defines when the settings allow (VolumeRenderer::program):
// llvmpipe evaluates pow() as exp2(log2()), two polynomial approximations per SIMD vector, at
// every trilinear sample, twice.
#ifndef VXL_HALF_VOXEL_STEP
#define VXL_HALF_VOXEL_STEP 0  // 1: uStep is half the smallest spacing, pow(x, 0.5) = sqrt(x)
#endif
#ifndef VXL_SHININESS
#define VXL_SHININESS 0  // 1..127: the specular exponent, an integer; 0: uPhong.w
#endif

// Opacity of a chord of `len` through matter of opacity `alpha` per unit length.
float correctedAlpha(float alpha, float len) {
  if (alpha <= 0.0 || len <= 0.0) return 0.0;
  return 1.0 - pow(1.0 - min(alpha, kMaxUnitAlpha), len / uUnit);
}

// correctedAlpha(alpha, uStep): the opacity of one trilinear step.
float stepAlpha(float alpha) {
#if VXL_HALF_VOXEL_STEP
  if (alpha <= 0.0) return 0.0;
  return 1.0 - sqrt(1.0 - min(alpha, kMaxUnitAlpha));
#else
  return correctedAlpha(alpha, uStep);
#endif
}

// x^shininess for x in [0, 1]: an integer exponent by 7 squarings, which the compiler unrolls.
float specularPower(float x) {
#if VXL_SHININESS > 0
  float r = 1.0, b = x;
  for (int i = 0; i < 7; ++i) {
    if (((VXL_SHININESS >> i) & 1) != 0) r *= b;
    b *= b;
  }
  return r;
#else
  return pow(x, uPhong.w);
#endif
}

// Phong terms of a sample with (premultiplied) colour c and opacity alpha: colour = ambient +
// shadow * lit. `gradient` is the opacity-weighted sum of unit gradient directions; the normal
// is -gradient, and shading is weighted by m = |gradient| / alpha, so a sample whose blended
// normals cancel fades to unlit colour. Mirrors shadeSample() in render/render_model.h.
// The normal and the reflected ray are never formed: n.l and r.e = 2 (n.l)(n.e) - l.e from dot
// products of the gradient (every trilinear pass runs this on llvmpipe; an inverse square root
// instead of the divisions cost more, docs/rendering-trilinear-profile.md, sixth session).
void shadeSampleToward(vec3 c, float alpha, vec3 gradient, vec3 toEye, vec3 toLight,
                       out vec3 ambient, out vec3 lit) {
  float len2 = dot(gradient, gradient);
  if (!uShadingEnabled || !(len2 > 0.0) || !(alpha > 0.0)) {
    ambient = c;
    lit = vec3(0.0);
    return;
  }
  float len = sqrt(len2);
  float m = min(len / alpha, 1.0);
  float ndl = -dot(gradient, toLight) / len;
  float diffuse = 0.0, specular = 0.0;
  if (ndl > 0.0) {
    diffuse = ndl;
    float nde = -dot(gradient, toEye) / len;
    specular = specularPower(max(2.0 * ndl * nde - dot(toLight, toEye), 0.0));
  }
  ambient = c * (1.0 - m + m * uPhong.x);
  lit = m * (c * (uPhong.y * diffuse) + vec3(alpha * uPhong.z * specular));
}

// The same towards the frame's directional light.
void shadeSample(vec3 c, float alpha, vec3 gradient, vec3 toEye, out vec3 ambient, out vec3 lit) {
  shadeSampleToward(c, alpha, gradient, toEye, uToLight, ambient, lit);
}

// A trilinear corner: colour and gradient direction weighted by the voxel's opacity.
void classifyCorner(uint bits, uint gradientCode, out vec4 colorAlpha, out vec3 gradient) {
  vec4 c = classify(bits);
  colorAlpha = vec4(0.0);
  gradient = vec3(0.0);
  if (c.a > 0.0) {
    colorAlpha = vec4(c.rgb * c.a, c.a);
    gradient = c.a * decodeGradient(gradientCode);
  }
}
