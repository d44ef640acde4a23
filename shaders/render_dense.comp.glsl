// SPDX-License-Identifier: BSD-3-Clause
// The dense 3D-texture ray caster (the benchmark's peer): same model, every voxel in textures.
#version 450
layout(local_size_x = 8, local_size_y = 8) in;

#include "common.glsl"
#include "camera.glsl"
#include "dda.glsl"
#include "gradient_codec.glsl"
#include "transfer_function.glsl"
#include "shading.glsl"
#include "dense_shadow.glsl"
#include "compositing.glsl"
#include "dense_traversal.glsl"
#include "render_main.glsl"
