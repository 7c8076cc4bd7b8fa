"""Renders one frame of an `mbfe simulate --vtk` animation to a PNG with VTK,
off screen (docs/animation.md): beams and bodies as tubes, spring contact
forces as arrows. Run under a virtual display when there is no screen:

    xvfb-run -a python3 scripts/render_frame.py DIR/frames/frame_000040.vtp out.png [--force-scale S]
"""
import argparse

import vtk

parser = argparse.ArgumentParser()
parser.add_argument("frame")
parser.add_argument("png")
parser.add_argument("--force-scale", type=float, default=4e-5, help="m of arrow per N")
parser.add_argument("--size", default="1200x420")
args = parser.parse_args()

reader = vtk.vtkXMLPolyDataReader()
reader.SetFileName(args.frame)
reader.Update()
data = reader.GetOutput()
bounds = data.GetBounds()
span = max(bounds[1] - bounds[0], bounds[3] - bounds[2])

tubes = vtk.vtkTubeFilter()
tubes.SetInputConnection(reader.GetOutputPort())
tubes.SetRadius(span * 0.003)
tubes.SetNumberOfSides(12)
tube_mapper = vtk.vtkPolyDataMapper()
tube_mapper.SetInputConnection(tubes.GetOutputPort())
tube_mapper.ScalarVisibilityOff()
tube_actor = vtk.vtkActor()
tube_actor.SetMapper(tube_mapper)
tube_actor.GetProperty().SetColor(0.15, 0.3, 0.6)

data.GetPointData().SetActiveVectors("contact_force")
arrow = vtk.vtkArrowSource()  # kept in a name: a temporary's output port would dangle
arrows = vtk.vtkGlyph3D()
arrows.SetInputData(data)
arrows.SetSourceConnection(arrow.GetOutputPort())
arrows.SetVectorModeToUseVector()
arrows.SetScaleModeToScaleByVector()
arrows.SetScaleFactor(args.force_scale)
arrows.OrientOn()
arrow_mapper = vtk.vtkPolyDataMapper()
arrow_mapper.SetInputConnection(arrows.GetOutputPort())
arrow_mapper.ScalarVisibilityOff()
arrow_actor = vtk.vtkActor()
arrow_actor.SetMapper(arrow_mapper)
arrow_actor.GetProperty().SetColor(0.85, 0.2, 0.1)

time = data.GetFieldData().GetArray("TIME").GetValue(0)
text = vtk.vtkTextActor()
text.SetInput(f"t = {time:.3f} s")
text.GetTextProperty().SetFontSize(22)
text.GetTextProperty().SetColor(0, 0, 0)
text.SetPosition(20, 20)

renderer = vtk.vtkRenderer()
renderer.SetBackground(1, 1, 1)
renderer.AddActor(tube_actor)
renderer.AddActor(arrow_actor)
renderer.AddActor2D(text)
width, height = (int(v) for v in args.size.split("x"))
window = vtk.vtkRenderWindow()
window.SetOffScreenRendering(1)
window.SetSize(width, height)
window.AddRenderer(renderer)
renderer.ResetCamera()
renderer.GetActiveCamera().Zoom(2.0)
window.Render()

capture = vtk.vtkWindowToImageFilter()
capture.SetInput(window)
capture.Update()
writer = vtk.vtkPNGWriter()
writer.SetFileName(args.png)
writer.SetInputConnection(capture.GetOutputPort())
writer.Write()
print("render_frame: wrote", args.png)
