"""The deformed body of a Tribos result, rendered by ParaView.

usage: xvfb-run -a pvbatch scripts/render.py DIR [--base NAME] [--field displacement|von_mises]
                                           [--scale S] [--out FILE.png]

Reads DIR/NAME.xmf (the XDMF index ParaView opens as it is: the body and the
contact points), warps the body by its displacement times S (default: the
largest displacement drawn as 5 % of the body's size), colours it by the
displacement magnitude [m] or the von Mises stress [Pa], draws the contact
nodes coloured by their status (0 no contact, 1 stick, 2 slip), moved by
their slip, seen from below the contact face, and writes
DIR/NAME_deformed.png.

Needs ParaView's pvbatch (Debian: apt-get install paraview) and, since
Debian's ParaView renders through X, a display: xvfb-run (apt-get install
xvfb). A missing one is reported with the command that installs it.
"""
import argparse
import glob
import math
import os
import sys

try:
    from paraview import simple as pv
except ImportError:
    sys.exit("render.py: run it with ParaView's pvbatch (apt-get install paraview), e.g.\n"
             "  xvfb-run -a pvbatch scripts/render.py DIR")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("directory")
    ap.add_argument("--base")
    ap.add_argument("--field", default="displacement", choices=["displacement", "von_mises"])
    ap.add_argument("--scale", type=float, default=0.0, help="displacement magnification (0: automatic)")
    ap.add_argument("--out")
    a = ap.parse_args()
    base = a.base
    if base is None:
        found = sorted(glob.glob(os.path.join(a.directory, "*.xmf")))
        if len(found) != 1:
            sys.exit("render.py: %s holds %d result indexes (*.xmf); name one with --base" % (a.directory, len(found)))
        base = os.path.splitext(os.path.basename(found[0]))[0]
    xmf = os.path.join(a.directory, base + ".xmf")
    if not os.path.exists(xmf):
        sys.exit("render.py: no result index %s" % xmf)

    reader = pv.XDMFReader(FileNames=[xmf])
    reader.UpdatePipeline()
    body = pv.ExtractBlock(Input=reader, Selectors=["/Root/body"])
    contact = pv.ExtractBlock(Input=reader, Selectors=["/Root/contact"])
    body.UpdatePipeline()
    contact.UpdatePipeline()

    # Magnification: the largest displacement as 5 % of the body's diagonal.
    info = body.GetDataInformation()
    bounds = info.GetBounds()
    size = math.sqrt(sum((bounds[2 * i + 1] - bounds[2 * i]) ** 2 for i in range(3)))
    umax = body.PointData["displacement"].GetRange(-1)[1]
    scale = a.scale if a.scale > 0 else (0.05 * size / umax if umax > 0 else 1.0)

    view = pv.CreateView("RenderView")
    view.ViewSize = [1200, 700]
    view.UseColorPaletteForBackground = 0  # a white page, not the palette's grey
    view.Background = [1, 1, 1]
    view.OrientationAxesVisibility = 1
    warped = pv.WarpByVector(Input=body, Vectors=["POINTS", "displacement"], ScaleFactor=scale)
    shown = pv.Show(warped, view)
    if a.field == "displacement":
        pv.ColorBy(shown, ("POINTS", "displacement", "Magnitude"))
        title = "|u| [m]"
    else:
        pv.ColorBy(shown, ("CELLS", "von_mises"))
        title = "von Mises stress [Pa]"
    shown.SetScalarBarVisibility(view, True)
    lut = pv.GetColorTransferFunction("displacement" if a.field == "displacement" else "von_mises")
    bar = pv.GetScalarBar(lut, view)
    bar.Title = title
    bar.ComponentTitle = ""
    bar.TitleColor = bar.LabelColor = [0, 0, 0]
    shown.EdgeColor = [0.2, 0.2, 0.2]
    shown.SetRepresentationType("Surface With Edges")
    shown.Ambient = 0.5  # the contact face is seen from below, away from the light
    shown.Diffuse = 0.6

    if contact.GetDataInformation().GetNumberOfPoints() > 0:
        # The contact points carry their slip (the tangential displacement);
        # a node in contact has no normal displacement beyond its gap, so
        # moving it by its slip puts it on the warped body.
        moved = pv.WarpByVector(Input=contact, Vectors=["POINTS", "slip"], ScaleFactor=scale)
        points = pv.Show(moved, view)
        points.SetRepresentationType("Points")
        points.PointSize = 8
        points.RenderPointsAsSpheres = 1
        pv.ColorBy(points, ("POINTS", "status"))
        status = pv.GetColorTransferFunction("status")
        status.InterpretValuesAsCategories = 1
        status.Annotations = ["0", "no contact", "1", "stick", "2", "slip"]
        status.IndexedColors = [0.7, 0.7, 0.7, 0.12, 0.47, 0.71, 1.0, 0.5, 0.05]
        points.SetScalarBarVisibility(view, True)
        pv.GetScalarBar(status, view).Title = "contact status"
        pv.GetScalarBar(status, view).TitleColor = pv.GetScalarBar(status, view).LabelColor = [0, 0, 0]

    view.CameraPosition = [bounds[1] + size, bounds[2] - 1.2 * size, bounds[4] - 0.6 * size]
    view.CameraFocalPoint = [0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3]), 0.5 * (bounds[4] + bounds[5])]
    view.CameraViewUp = [0, 0, 1]
    view.ResetCamera()
    text = pv.Text(Text="%s: displacement x %.3g" % (base, scale))
    label = pv.Show(text, view)
    label.Color = [0, 0, 0]
    label.FontSize = 14
    out = a.out or os.path.join(a.directory, base + "_deformed.png")
    pv.SaveScreenshot(out, view, ImageResolution=[1200, 700])
    print(out)


if __name__ == "__main__":
    main()
