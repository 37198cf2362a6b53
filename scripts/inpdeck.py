#!/usr/bin/env python3
"""An Abaqus-style .inp deck of 8-node hexahedra read into plain Python: the scripts that build
cases from the project's meshes (scripts/peer_calculix_pairs.py, scripts/make_cup_elastic_holder.py)."""


def read_inp(path):
    """nodes {id: (x, y, z)}, elements [(id, [8 ids], elset)], node sets {name: [ids]} of the deck"""
    X, elems, nsets = {}, [], {}
    mode, name = None, None
    for line in open(path):
        s = line.strip()
        if not s or s.startswith("**"):
            continue
        if s.startswith("*"):
            parts = [p.strip() for p in s[1:].split(",")]
            kw = parts[0].upper()
            opts = {k.strip().upper(): v.strip() for k, _, v in (p.partition("=") for p in parts[1:])}
            mode, name = kw, None
            if kw == "ELEMENT":
                name = opts.get("ELSET")
            elif kw == "NSET":
                name = opts["NSET"]
                nsets.setdefault(name, [])
            continue
        v = [p for p in s.replace(",", " ").split()]
        if mode == "NODE":
            X[int(v[0])] = tuple(float(p) for p in v[1:4])
        elif mode == "ELEMENT":
            elems.append((int(v[0]), [int(p) for p in v[1:9]], name))
        elif mode == "NSET":
            nsets[name].extend(int(p) for p in v)
    return X, elems, nsets
