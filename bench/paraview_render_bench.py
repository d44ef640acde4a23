# SPDX-License-Identifier: BSD-3-Clause
"""ParaView's volume ray caster on the rendering benchmark's protocol (docs/rendering-benchmark.md).

Run in pvpython (ParaView 5.11 ships VTK 9.2): `pvpython --no-mpi bench/paraview_render_bench.py
DENSE.nrrd TF.tf.json --size 1000x1000 --frames-per-turn 6`. DENSE.nrrd is `voxlink export` of the
benchmark's .vxl, so both renderers see the same kept values. ParaView's Volume representation
renders vtkImageData through vtkSmartVolumeMapper (vtkOpenGLGPUVolumeRayCastMapper underneath),
but its multi-block wrapper in 5.11 hides the sample distance; this script drives the GPU mapper
itself so the settings can be matched with `voxlink bench-render`:
  - sample distance: STEP voxels of the smallest spacing, AutoAdjustSampleDistances and
    LockSampleDistanceToInputSpacing off (ParaView's default adjusts it from the frame time).
    Not through vtkSmartVolumeMapper: in VTK 9.2 its SetSampleDistance did not reach the GPU
    mapper (the foot at step 0.5 and at step 4 gave the same image, byte for byte, and the same
    time), which kept its own distance from the input spacing;
  - the TF's opacities are per unit length of the smallest spacing (ScalarOpacityUnitDistance);
  - Phong shading on with voxlink's defaults (ambient 0.3, diffuse 0.7, specular 0.25, power 24)
    and its light: a camera light from (0.35, 0.5, 1) in camera space;
  - voxlink's camera: framing of the world box (azimuth 30, elevation 20, z up, 30 deg field of
    view), then the paper's orbit (360 deg about world y, then about world x).
Differences that remain: VTK computes gradients from the values on the fly (voxlink stores them),
VTK jitters nothing here and stops rays at its own opacity threshold.
Prints one line: frames, mean, median, min and max ms per frame.
"""
import argparse
import json
import math
import statistics
import sys
import time

import vtkmodules.vtkCommonDataModel as vtk_data
import vtkmodules.vtkIOImage as vtk_io
import vtkmodules.vtkRenderingCore as vtk_render
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (registers the OpenGL render window)
import vtkmodules.vtkRenderingVolumeOpenGL2 as vtk_volume
import vtkmodules.vtkCommonColor  # noqa: F401


def rotation(axis, degrees):
    """Rotation matrix about a unit axis (right-handed), as render::Camera's rotation()."""
    x, y, z = axis
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    t = 1 - c
    return [[t * x * x + c, t * x * y - s * z, t * x * z + s * y],
            [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
            [t * x * z - s * y, t * y * z + s * x, t * z * z + c]]


def apply(m, v):
    return [sum(m[i][j] * v[j] for j in range(3)) for i in range(3)]


def protocol_cameras(lo, hi, frames_per_turn, fov=30.0, azimuth=30.0, elevation=20.0):
    """(eye, target, up) per frame: Camera::framing with z up, then protocolCamera()."""
    target = [(a + b) / 2 for a, b in zip(lo, hi)]
    radius = 0.5 * math.dist(lo, hi)
    az, el = math.radians(azimuth), math.radians(elevation)
    back = [math.sin(az) * math.cos(el), -math.cos(az) * math.cos(el), math.sin(el)]
    distance = radius / math.sin(math.radians(fov) / 2)
    up = [0.0, 0.0, 1.0]
    right = [up[1] * back[2] - up[2] * back[1], up[2] * back[0] - up[0] * back[2],
             up[0] * back[1] - up[1] * back[0]]
    norm = math.sqrt(sum(r * r for r in right))
    right = [r / norm for r in right]
    cam_up = [back[1] * right[2] - back[2] * right[1], back[2] * right[0] - back[0] * right[2],
              back[0] * right[1] - back[1] * right[0]]
    step = 360.0 / frames_per_turn
    out = []
    for i in range(2 * frames_per_turn):
        if i < frames_per_turn:
            r = rotation([0, 1, 0], step * i)
        else:
            r = rotation([1, 0, 0], step * (i - frames_per_turn))
        b, u = apply(r, back), apply(r, cam_up)
        out.append(([t + distance * x for t, x in zip(target, b)], target, u))
    return out


def main():
    p = argparse.ArgumentParser()
    p.add_argument("volume")
    p.add_argument("tf")
    p.add_argument("--size", default="1000x1000")
    p.add_argument("--frames-per-turn", type=int, default=6)
    p.add_argument("--step", type=float, default=0.5, help="sample distance in voxels")
    p.add_argument("--no-shading", action="store_true")
    p.add_argument("--picture", help="PNG of the first frame")
    a = p.parse_args()
    width, height = (int(x) for x in a.size.split("x"))
    with open(a.tf) as f:
        tf = json.load(f)

    reader = vtk_io.vtkNrrdReader()
    reader.SetFileName(a.volume)
    reader.Update()
    image = reader.GetOutput()
    if image.GetNumberOfPoints() == 0:
        sys.exit(f"paraview_render_bench: {a.volume}: no voxels read")
    spacing, origin, dims = image.GetSpacing(), image.GetOrigin(), image.GetDimensions()
    unit = min(spacing)

    opacity = vtk_data.vtkPiecewiseFunction()
    for value, alpha in tf["opacity"]:
        opacity.AddPoint(value, alpha)
    color = vtk_render.vtkColorTransferFunction()
    color.SetColorSpaceToRGB()
    for value, r, g, b in tf["color"]:
        color.AddRGBPoint(value, r, g, b)
    prop = vtk_render.vtkVolumeProperty()
    prop.SetScalarOpacity(opacity)
    prop.SetColor(color)
    prop.SetInterpolationTypeToLinear()
    prop.SetScalarOpacityUnitDistance(unit)
    if not a.no_shading:
        prop.ShadeOn()
        prop.SetAmbient(0.3)
        prop.SetDiffuse(0.7)
        prop.SetSpecular(0.25)
        prop.SetSpecularPower(24.0)

    mapper = vtk_volume.vtkOpenGLGPUVolumeRayCastMapper()
    mapper.SetInputData(image)
    mapper.AutoAdjustSampleDistancesOff()
    mapper.LockSampleDistanceToInputSpacingOff()
    mapper.SetSampleDistance(a.step * unit)
    volume = vtk_render.vtkVolume()
    volume.SetMapper(mapper)
    volume.SetProperty(prop)

    renderer = vtk_render.vtkRenderer()
    renderer.AddVolume(volume)
    renderer.SetBackground(0, 0, 0)
    light = vtk_render.vtkLight()
    light.SetLightTypeToCameraLight()
    light.SetPosition(0.35, 0.5, 1.0)
    light.SetFocalPoint(0, 0, 0)
    renderer.AddLight(light)
    window = vtk_render.vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(width, height)
    window.AddRenderer(renderer)

    lo = [o - s / 2 for o, s in zip(origin, spacing)]
    hi = [o + (n - 0.5) * s for o, n, s in zip(origin, dims, spacing)]
    camera = renderer.GetActiveCamera()
    camera.SetViewAngle(30.0)
    cameras = protocol_cameras(lo, hi, a.frames_per_turn)

    def render(eye, target, up):
        camera.SetPosition(*eye)
        camera.SetFocalPoint(*target)
        camera.SetViewUp(*up)
        renderer.ResetCameraClippingRange()
        window.Render()
        window.WaitForCompletion()  # glFinish, as bench-render does

    render(*cameras[0])  # warm-up: texture upload and shader compilation, not timed
    times = []
    for i, cam in enumerate(cameras):
        t0 = time.perf_counter()
        render(*cam)
        times.append(1e3 * (time.perf_counter() - t0))
        if i == 0 and a.picture:
            grab = vtk_render.vtkWindowToImageFilter()
            grab.SetInput(window)
            grab.ReadFrontBufferOff()
            grab.Update()
            png = vtk_io.vtkPNGWriter()
            png.SetFileName(a.picture)
            png.SetInputConnection(grab.GetOutputPort())
            png.Write()
    print(f"paraview {width}x{height} step {a.step} shading {'off' if a.no_shading else 'on'}: "
          f"frames {len(times)} mean {statistics.mean(times):.1f} median "
          f"{statistics.median(times):.1f} min {min(times):.1f} max {max(times):.1f} ms")


if __name__ == "__main__":
    main()
