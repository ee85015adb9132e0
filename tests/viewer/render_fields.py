# Opens a run's fields.xmf with ParaView's XDMF reader in its own Python (pvpython, ParaView
# 5.11 as Debian 12 packages it), renders the last frame (particles as points, hexahedra as
# surfaces, coloured by speed) and writes a PNG; exits non-zero when a block (particles,
# hexahedra) arrives without points or the mesh without cells, or when the picture is blank
# (fewer than 2 % of its pixels differ from the white background). Under a virtual display of
# 24-bit colour (the default 8-bit screen has no GLX visual ParaView accepts):
#   xvfb-run -a -s "-screen 0 1024x768x24" pvpython tests/viewer/render_fields.py RUN/fields.xmf OUT.png
import sys

from paraview.simple import (ColorBy, GetActiveViewOrCreate, GetAnimationScene,
                             GetColorTransferFunction, GetScalarBar, Render, ResetCamera,
                             SaveScreenshot, Show, UpdatePipeline, XDMFReader)
from paraview import servermanager
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.util.numpy_support import vtk_to_numpy

fields, png = sys.argv[1], sys.argv[2]
reader = XDMFReader(FileNames=[fields])
scene = GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
scene.AnimationTime = reader.TimestepValues[-1]
UpdatePipeline(time=reader.TimestepValues[-1], proxy=reader)

# Every block (particles, hexahedra) must arrive with its points, and the mesh with its cells.
data = servermanager.Fetch(reader)
blocks = {}
it = data.NewIterator()
it.InitTraversal()
while not it.IsDoneWithTraversal():
    meta = it.GetCurrentMetaData()
    name = meta.Get(data.NAME()) if meta is not None and meta.Has(data.NAME()) else "?"
    block = it.GetCurrentDataObject()
    blocks[name] = (block.GetNumberOfPoints(), block.GetNumberOfCells())
    it.GoToNextItem()
print("blocks (points, cells):", blocks)
if len(blocks) < 2 or any(points == 0 for points, _ in blocks.values()):
    sys.exit("ParaView read an empty or missing block from " + fields)
if any(name.startswith("hexahedra") and cells == 0 for name, (_, cells) in blocks.items()):
    sys.exit("ParaView read the hexahedra without their cells from " + fields)

view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [800, 600]
view.UseColorPaletteForBackground = 0
view.Background = [1.0, 1.0, 1.0]
view.OrientationAxesVisibility = 0
display = Show(reader, view)
display.SetRepresentationType("Surface")
display.PointSize = 3.0
ColorBy(display, ("POINTS", "velocity", "Magnitude"))
display.RescaleTransferFunctionToDataRange(True, False)
display.SetScalarBarVisibility(view, True)
bar = GetScalarBar(GetColorTransferFunction("velocity"), view)
bar.Title = "speed"
bar.ComponentTitle = ""
bar.TitleColor = [0.0, 0.0, 0.0]
bar.LabelColor = [0.0, 0.0, 0.0]
view.CameraPosition = [60.0, -60.0, 20.0]
view.CameraFocalPoint = [10.0, 10.0, 2.0]
view.CameraViewUp = [0.0, 0.0, 1.0]
ResetCamera(view)
Render(view)
SaveScreenshot(png, view, ImageResolution=[800, 600])

image = vtkPNGReader()
image.SetFileName(png)
image.Update()
pixels = vtk_to_numpy(image.GetOutput().GetPointData().GetScalars())[:, :3].astype(int)
drawn = (abs(pixels - 255).sum(axis=1) > 30).mean()
print("pixels differing from the white background: %.1f %%" % (100 * drawn))
if drawn < 0.02:
    sys.exit("the picture is blank: " + png)
