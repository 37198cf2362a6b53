"""Off-screen picture of the deformed sheet coloured by the equivalent plastic strain.

usage: pvpython --force-offscreen-rendering scripts/render.py OUTDIR [picture.png] [--field plastic_strain]
       [--mirror]   (a quarter model shown as the full sheet, mirrored about x = 0 and y = 0)
Reads OUTDIR/fields.xmf (the XDMF index of the HDF5 fields), takes the last output time, warps the
mesh by the displacement, colours the cells by the field and writes the PNG."""
import os
import sys

from paraview.simple import *  # noqa: F401,F403  (ParaView's scripting interface)

args = [a for a in sys.argv[1:] if not a.startswith("--")]
field = "plastic_strain"
for i, a in enumerate(sys.argv):
    if a == "--field" and i + 1 < len(sys.argv):
        field = sys.argv[i + 1]
        args = [x for x in args if x != field]
mirror = "--mirror" in sys.argv
if not args:
    print(__doc__)
    sys.exit(2)
outdir = args[0]
png = args[1] if len(args) > 1 else os.path.join(outdir, "render.png")
xmf = os.path.join(outdir, "fields.xmf")
if not os.path.exists(xmf):
    print(f"render.py: {xmf} not found", file=sys.stderr)
    sys.exit(1)

reader = XDMFReader(FileNames=[xmf])
reader.UpdatePipelineInformation()
times = list(reader.TimestepValues) if hasattr(reader.TimestepValues, "__len__") else [reader.TimestepValues]
t = float(times[-1]) if times else 0.0
warp = WarpByVector(Input=reader)
warp.Vectors = ["POINTS", "displacement"]
src = warp
if mirror:
    rx = Reflect(Input=warp)
    rx.Plane = "X"
    rx.CopyInput = 1
    ry = Reflect(Input=rx)
    ry.Plane = "Y"
    ry.CopyInput = 1
    src = ry
view = CreateView("RenderView")
view.ViewSize = [1200, 800]
view.OrientationAxesVisibility = 0
view.Background = [1, 1, 1]
try:
    view.UseColorPaletteForBackground = 0
except AttributeError:
    pass
view.ViewTime = float(t)
disp = Show(src, view)
ColorBy(disp, ("CELLS", field))
lut = GetColorTransferFunction(field)
lut.ApplyPreset("Jet", True)
disp.RescaleTransferFunctionToDataRange(False, True)
disp.SetScalarBarVisibility(view, True)
bar = GetScalarBar(lut, view)
bar.Title = field.replace("_", " ")
bar.ComponentTitle = ""
bar.TitleColor = [0, 0, 0]
bar.LabelColor = [0, 0, 0]
view.CameraPosition = [-90, -150, 110]
view.CameraFocalPoint = [0, 0, 10]
view.CameraViewUp = [0, 0, 1]
view.ResetCamera()
Render(view)
SaveScreenshot(png, view, ImageResolution=[1200, 800])
print(f"wrote {png} (time {t})")
