"""Render a dynamic run's ParaView files (`rodlab dynamic --vtk DIR`) headless with pvpython.

    pvpython --force-offscreen-rendering scripts/paraview_figure.py DIR/rod.pvd OUT.png \
        [--snapshots K] [--size WIDTH HEIGHT]

Draws K snapshots of the rod spread evenly over the run's times (the first and the last
included), each as a tube of the rod's real radius (ParaView's Tube filter on the point
array `radius`) coloured by the magnitude of the internal moment `moment`, the earlier
snapshots fainter, seen along the axis normal to the plane of the motion. This is the
pipeline docs/visualisation.md describes for the ParaView GUI, as a script; `make
paraview-figure` renders docs/figures/paraview-swing.png with it.

Exit status: 0 written; 2 bad usage or a collection without times.
"""

import argparse
import sys

from paraview import simple as pv


def parse_arguments(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("collection", help="rod.pvd written by --vtk")
    parser.add_argument("out", help="the image to write (.png)")
    parser.add_argument("--snapshots", type=int, default=5, help="snapshots drawn (>= 1)")
    parser.add_argument("--size", type=int, nargs=2, default=[1200, 800], metavar=("W", "H"))
    arguments = parser.parse_args(argv)
    if arguments.snapshots < 1:
        parser.error("--snapshots must be >= 1")
    return arguments


def snapshot_times(times, count):
    """`count` of the collection's times, evenly spread, the first and the last included."""
    if count == 1:
        return [times[-1]]
    last = len(times) - 1
    return [times[round(k * last / (count - 1))] for k in range(count)]


def rod_tube(reader, time):
    """The rod at `time` as a tube of its real radius (point array `radius`)."""
    frozen = pv.ForceTime(Input=reader)
    frozen.IgnorePipelineTime = 1
    frozen.ForcedTime = time
    tube = pv.Tube(Input=frozen)
    tube.Scalars = ["POINTS", "radius"]
    tube.VaryRadius = "By Absolute Scalar"
    tube.RadiusFactor = 1.0
    tube.NumberofSides = 24
    tube.Capping = 1
    return tube


def largest_moment(reader, times):
    """The largest |moment| over the snapshots: one colour scale for all of them."""
    largest = 0.0
    for time in times:
        reader.UpdatePipeline(time)
        low, high = reader.PointData["moment"].GetRange(-1)
        largest = max(largest, high)
    return largest


def main(argv):
    arguments = parse_arguments(argv)
    reader = pv.PVDReader(FileName=arguments.collection)
    times = list(reader.TimestepValues) if reader.TimestepValues else []
    if len(times) < 2:
        print(f"paraview_figure: {arguments.collection}: not a time series", file=sys.stderr)
        return 2
    shown = snapshot_times(times, arguments.snapshots)

    view = pv.CreateView("RenderView")
    view.ViewSize = arguments.size
    view.Background = [1.0, 1.0, 1.0]
    view.OrientationAxesVisibility = 0
    try:
        view.UseColorPaletteForBackground = 0
    except AttributeError:
        pass  # older ParaView: the background is used as set

    moment_colours = pv.GetColorTransferFunction("moment")
    moment_colours.ApplyPreset("Viridis (matplotlib)", True)
    moment_colours.VectorMode = "Magnitude"
    moment_colours.AutomaticRescaleRangeMode = "Never"

    for index, time in enumerate(shown):
        display = pv.Show(rod_tube(reader, time), view)
        pv.ColorBy(display, ("POINTS", "moment", "Magnitude"))
        display.LookupTable = moment_colours
        display.Opacity = 0.35 + 0.65 * (index + 1) / len(shown)
    moment_colours.RescaleTransferFunction(0.0, largest_moment(reader, shown))
    bar = pv.GetScalarBar(moment_colours, view)
    bar.Title = "|internal moment| [N m]"
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0.1, 0.1, 0.1]
    bar.Visibility = 1

    label = pv.Text(Text="t = " + ", ".join(f"{time:.3g}" for time in shown) + " s")
    label_display = pv.Show(label, view)
    label_display.Color = [0.1, 0.1, 0.1]
    label_display.WindowLocation = "Upper Center"
    label_display.FontSize = 14

    view.CameraPosition = [0.0, -1.0, 0.0]
    view.CameraFocalPoint = [0.0, 0.0, 0.0]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.ResetCamera()
    pv.SaveScreenshot(arguments.out, view, ImageResolution=arguments.size,
                      TransparentBackground=0)
    pv.Delete(view)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
