// SPDX-License-Identifier: BSD-3-Clause
// Renders a VoxLink file: one thread per pixel, a primary ray composited front to back.
#version 450
layout(local_size_x = 8, local_size_y = 8) in;

#include "common.glsl"
#include "camera.glsl"
#include "dda.glsl"
#include "gradient_codec.glsl"
#include "transfer_function.glsl"
#include "shading.glsl"
#include "voxlink_access.glsl"
#include "voxlink_brick_bounds.glsl"
#include "voxlink_row_walk.glsl"
#include "voxlink_scene.glsl"
#include "voxlink_dynamic.glsl"
#include "voxlink_shadow.glsl"
#include "voxlink_scene_shading.glsl"
#if VXL_SHADOW_CACHE
#include "shadow_cache.glsl"
#endif
#include "compositing.glsl"
#include "voxlink_voxels.glsl"
#include "voxlink_dynamic_trace.glsl"
#include "voxlink_trilinear.glsl"
#include "render_main.glsl"
