#!/usr/bin/env python3
"""Validate a fields.h5 written by src/output.c (and its fields.xmf index when present).

usage: check_fields.py DIR_or_fields.h5 [-q]

Prints the groups and datasets, then checks: /mesh/coordinates (nv x 3, float),
/mesh/hexahedra (ne x 8, integer, entries in [0, nv)), /mesh/node_ids (nv), /mesh/element_ids
(ne); every /steps/NNNNNN group has the attributes time and step (step == NNNNNN) and datasets
of nv or ne rows (1D, or 2D with ncomp columns) matching their "center" attribute; the XDMF
parses, has one <Time> per step group in the same order, and points only to existing datasets.
Exit code 0 when valid, 1 otherwise.
"""
import os
import sys
import xml.etree.ElementTree as ET

import h5py
import numpy as np


def main(argv):
    args = [a for a in argv[1:] if not a.startswith("-")]
    quiet = "-q" in argv[1:]
    if len(args) != 1:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    path = args[0]
    h5path = os.path.join(path, "fields.h5") if os.path.isdir(path) else path
    xmfpath = os.path.join(os.path.dirname(os.path.abspath(h5path)), "fields.xmf")
    errors = []

    def err(msg):
        errors.append(msg)
        print("ERROR: " + msg)

    with h5py.File(h5path, "r") as f:
        if not quiet:
            def show(name, obj):
                attrs = ", ".join("%s=%s" % (k, obj.attrs[k]) for k in obj.attrs)
                if isinstance(obj, h5py.Dataset):
                    print("  %-40s dataset %-12s %-8s %s" % ("/" + name, obj.shape, obj.dtype, attrs))
                else:
                    print("  %-40s group %s" % ("/" + name, attrs))
            print(h5path)
            f.visititems(show)

        nv = ne = None
        m = f.get("mesh")
        if m is None:
            err("no /mesh group")
        else:
            X = m.get("coordinates")
            H = m.get("hexahedra")
            if X is None or X.ndim != 2 or X.shape[1] != 3 or X.dtype.kind != "f":
                err("/mesh/coordinates must be nv x 3 floats")
            else:
                nv = X.shape[0]
                if not np.all(np.isfinite(X[()])):
                    err("/mesh/coordinates has non-finite values")
            if H is None or H.ndim != 2 or H.shape[1] != 8 or H.dtype.kind not in "iu":
                err("/mesh/hexahedra must be ne x 8 integers")
            else:
                ne = H.shape[0]
                if nv is not None and ne > 0:
                    h = H[()]
                    if h.min() < 0 or h.max() >= nv:
                        err("/mesh/hexahedra entries outside [0, %d)" % nv)
            for name, n in (("node_ids", nv), ("element_ids", ne)):
                d = m.get(name)
                if d is None or d.ndim != 1 or (n is not None and d.shape[0] != n):
                    err("/mesh/%s must be 1D of length %s" % (name, n))

        steps = []
        for gname in sorted(f.get("steps", {}).keys()):
            g = f["steps"][gname]
            if "time" not in g.attrs or "step" not in g.attrs:
                err("/steps/%s lacks the time or step attribute" % gname)
                continue
            if int(g.attrs["step"]) != int(gname):
                err("/steps/%s has step attribute %s" % (gname, g.attrs["step"]))
            steps.append((gname, float(g.attrs["time"])))
            for dname, d in g.items():
                center = d.attrs.get("center", b"")
                center = center.decode() if isinstance(center, bytes) else str(center)
                n = {"node": nv, "cell": ne}.get(center)
                if center not in ("node", "cell"):
                    err("/steps/%s/%s: center attribute %r" % (gname, dname, center))
                elif d.ndim not in (1, 2) or d.shape[0] != n:
                    err("/steps/%s/%s: shape %s, expected %d rows (%s field)" % (gname, dname, d.shape, n, center))
                elif not np.all(np.isfinite(d[()])):
                    err("/steps/%s/%s has non-finite values" % (gname, dname))

        if os.path.exists(xmfpath):
            try:
                root = ET.parse(xmfpath).getroot()
            except ET.ParseError as e:
                err("%s does not parse: %s" % (xmfpath, e))
                root = None
            if root is not None:
                grids = root.findall("./Domain/Grid/Grid")
                times = [float(gr.find("Time").get("Value")) for gr in grids]
                if times != [t for _, t in steps]:
                    err("fields.xmf times %s differ from the file's %s" % (times, [t for _, t in steps]))
                for item in root.iter("DataItem"):
                    fname, _, dpath = item.text.strip().partition(":")
                    if fname != "fields.h5":
                        err("fields.xmf refers to %r, not the relative name fields.h5" % fname)
                    elif dpath not in f:
                        err("fields.xmf refers to missing dataset %s" % dpath)
                    else:
                        dims = tuple(int(x) for x in item.get("Dimensions").split())
                        if dims != f[dpath].shape:
                            err("fields.xmf: %s Dimensions %s, dataset shape %s" % (dpath, dims, f[dpath].shape))
            if os.path.exists(xmfpath + ".tmp"):
                err("leftover %s.tmp" % xmfpath)

    print("%s: nv=%s ne=%s steps=%d, %s" % (h5path, nv, ne, len(steps), "OK" if not errors else "%d error(s)" % len(errors)))
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
