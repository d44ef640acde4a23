#version 450
// GL voxelization, vertex stage: one orthographic view per dominant axis (the paper's swizzle).
// The host draws the triangles whose normal is dominant along uAxis; this stage projects their
// grid coordinates onto the plane of the other two axes (u = axis + 1, v = axis + 2, mod 3) so
// that pixel (u, v) is the column of voxels (u, v) and the fragment depth is the grid
// coordinate along uAxis.
layout(std430, binding = 2) readonly buffer Positions { float positions[]; };  // grid coords
layout(std430, binding = 3) readonly buffer Indices { uint indices[]; };
layout(std430, binding = 4) readonly buffer Order { uint order[]; };  // triangles by axis

uniform int uAxis;
uniform float uViewportEdge;  // square viewport, pixels
uniform uint uFirst;          // first entry of `order` in this draw

noperspective out float vDepth;
flat out uint vTriangle;

void main() {
  uint triangle = order[uFirst + uint(gl_VertexID) / 3u];
  uint vertex = indices[3u * triangle + uint(gl_VertexID) % 3u];
  vec3 g = vec3(positions[3u * vertex], positions[3u * vertex + 1u], positions[3u * vertex + 2u]);
  vec2 uv = vec2(g[(uAxis + 1) % 3], g[(uAxis + 2) % 3]);
  gl_Position = vec4(uv / uViewportEdge * 2.0 - 1.0, 0.0, 1.0);
  vDepth = g[uAxis];
  vTriangle = triangle;
}
