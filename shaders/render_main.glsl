// The pixel loop shared by render_voxlink.comp.glsl and render_dense.comp.glsl, included after
// the traversal that defines traceVoxels() and traceTrilinear().

layout(rgba32f, binding = 0) uniform writeonly image2D uTarget;
uniform vec3 uBackground;

void main() {
  uvec2 pixel = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(pixel, uImageSize))) return;
  vec3 direction = primaryDirection(pixel);
  vec3 o = worldToIndex(uEyeWorld);
  vec3 d = directionToIndex(direction);
  vec2 range = intersectBox(o, d, vec3(uDims));
  float t0 = max(range.x, 0.0), t1 = range.y;
  vec3 color = vec3(0.0);
  float transmittance = 1.0;
  if (t0 < t1) {
#if VXL_TRILINEAR
    traceTrilinear(o, d, t0, t1, -direction, color, transmittance);
#else
    traceVoxels(o, d, t0, t1, -direction, color, transmittance);
#endif
  }
  imageStore(uTarget, ivec2(pixel), vec4(color + transmittance * uBackground, 1.0 - transmittance));
}
