#version 450
// SPDX-License-Identifier: BSD-3-Clause
// GL voxelization, vertex stage: one orthographic view per dominant axis (the paper's swizzle).
// The host draws the triangles whose normal is dominant along uAxis; this stage projects their
// grid coordinates onto the plane of the other two axes (u = axis + 1, v = axis + 2, mod 3) so
// that pixel (u, v) is the column of voxels (u, v) and the fragment depth is the grid
// coordinate along uAxis.
//
// uConservative: llvmpipe has no conservative rasterization, so it is emulated (Hasselgren,
// Akenine-Moller, Ohlsson, GPU Gems 2 ch. 42): each edge is pushed out by the pixel's
// semidiagonal and the corner moved to where its two pushed edges meet, so every pixel the
// triangle touches gets a fragment; the fragment stage drops the ones it does not touch. The push
// is 1 % of a pixel more than the semidiagonal, so that pixels the triangle only touches are not
// left to the rasterizer's tie rule.
layout(std430, binding = 2) readonly buffer Positions { float positions[]; };  // grid coords
layout(std430, binding = 3) readonly buffer Indices { uint indices[]; };
layout(std430, binding = 4) readonly buffer Order { uint order[]; };  // triangles by axis
#ifdef VXL_DYN_N
// The dynamic layer: per triangle area x unit normal in fixed point, material + 1.
layout(std430, binding = 8) readonly buffer Contributions { ivec4 contributions[]; };
#endif

uniform int uAxis;
uniform float uViewportEdge;  // square viewport, pixels
uniform uint uFirst;          // first entry of `order` in this draw
uniform bool uConservative;

noperspective out float vDepth;
flat out uint vTriangle;
// The triangle's corners in (u, v, depth), the same from each of its vertices: the fragment stage
// reads them here instead of from the buffers, once per fragment (measured: the raster is the
// dynamic layer's largest cost on llvmpipe).
flat out vec3 vCorner0, vCorner1, vCorner2;
flat out ivec4 vContribution;

vec3 corner(uint triangle, uint c) {
  uint vertex = indices[3u * triangle + c];
  vec3 g = vec3(positions[3u * vertex], positions[3u * vertex + 1u], positions[3u * vertex + 2u]);
  return vec3(g[(uAxis + 1) % 3], g[(uAxis + 2) % 3], g[uAxis]);  // (u, v, depth)
}

void main() {
  uint triangle = order[uFirst + uint(gl_VertexID) / 3u];
  uint c = uint(gl_VertexID) % 3u;
  vec3 p = corner(triangle, c);
  vec2 uv = p.xy;
  if (uConservative) {
    vec2 a = corner(triangle, (c + 2u) % 3u).xy, b = corner(triangle, (c + 1u) % 3u).xy;
    float orientation = sign((p.x - a.x) * (b.y - a.y) - (p.y - a.y) * (b.x - a.x));
    // Outward normals of the edges a -> p and p -> b, and their pushed lines n . x = d.
    vec2 d1 = p.xy - a, d2 = b - p.xy;
    vec2 n1 = orientation * vec2(d1.y, -d1.x), n2 = orientation * vec2(d2.y, -d2.x);
    float c1 = dot(n1, p.xy) + 0.5 * (abs(n1.x) + abs(n1.y)) + 0.01 * length(n1);
    float c2 = dot(n2, p.xy) + 0.5 * (abs(n2.x) + abs(n2.y)) + 0.01 * length(n2);
    float det = n1.x * n2.y - n1.y * n2.x;
    if (det != 0.0) uv = vec2(c1 * n2.y - c2 * n1.y, n1.x * c2 - n2.x * c1) / det;
  }
  gl_Position = vec4(uv / uViewportEdge * 2.0 - 1.0, 0.0, 1.0);
  vDepth = p.z;
  vTriangle = triangle;
  vCorner0 = corner(triangle, 0u);
  vCorner1 = corner(triangle, 1u);
  vCorner2 = corner(triangle, 2u);
#ifdef VXL_DYN_N
  vContribution = contributions[triangle];
#else
  vContribution = ivec4(0);
#endif
}
