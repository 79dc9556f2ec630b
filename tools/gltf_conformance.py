#!/usr/bin/env python3
"""Writes the glTF conformance set under tests/gltf/: one small file per glTF feature the loader
reads, converts or refuses, each with values a test can check exactly (tests/unit/
test_gltf_conformance.c, tests/e2e/gltf_conformance.sh). Made here, by hand, from the glTF 2.0
specification; nothing downloaded. The outputs are committed, so CI does not run this script;
re-run it (`python3 tools/gltf_conformance.py`) after changing it, and commit what changes.

Every file draws in the z = 0 plane facing +z unless it says otherwise, and has no lights (the
default studio lights it) and no camera (the default camera frames it) unless it says otherwise."""
import base64
import json
import math
import os
import struct
import zlib

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "gltf")


def png_rgb(width, height, pixels):
    """A minimal 8-bit RGB PNG (no filter), pixels as rows of (r, g, b) tuples."""
    raw = b"".join(b"\x00" + bytes(c for px in row for c in px) for row in pixels)

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


def png_rgba(width, height, pixels):
    """A minimal 8-bit RGBA PNG (no filter), pixels as rows of (r, g, b, a) tuples."""
    raw = b"".join(b"\x00" + bytes(c for px in row for c in px) for row in pixels)

    def chunk(kind, data):
        body = kind + data
        return struct.pack(">I", len(data)) + body + struct.pack(">I", zlib.crc32(body) & 0xFFFFFFFF)

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 6, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


# The checker every textured file uses: top row red, green; bottom row blue, white.
CHECKER = png_rgb(2, 2, [[(255, 0, 0), (0, 255, 0)], [(0, 0, 255), (255, 255, 255)]])


class Doc:
    """A glTF document with one binary buffer assembled as views are added."""

    def __init__(self):
        self.bin = bytearray()
        self.j = {"asset": {"version": "2.0", "generator": "gikiosk tools/gltf_conformance.py"},
                  "scene": 0, "scenes": [{"nodes": []}], "nodes": [], "meshes": [], "accessors": [],
                  "bufferViews": [], "buffers": []}

    def view(self, data, target=None):
        while len(self.bin) % 4:
            self.bin.append(0)
        v = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)}
        if target:
            v["target"] = target
        self.bin += data
        self.j["bufferViews"].append(v)
        return len(self.j["bufferViews"]) - 1

    def accessor(self, fmt, values, ctype, atype, normalized=False, minmax=False, target=None):
        data = b"".join(struct.pack("<" + fmt, *v) if isinstance(v, tuple) else struct.pack("<" + fmt, v)
                        for v in values)
        a = {"bufferView": self.view(data, target), "componentType": ctype, "count": len(values), "type": atype}
        if normalized:
            a["normalized"] = True
        if minmax:
            a["min"] = [min(v[i] for v in values) for i in range(len(values[0]))]
            a["max"] = [max(v[i] for v in values) for i in range(len(values[0]))]
        self.j["accessors"].append(a)
        return len(self.j["accessors"]) - 1

    def mesh_node(self, primitives, name, **node):
        self.j["meshes"].append({"name": name, "primitives": primitives})
        n = dict(node, name=name, mesh=len(self.j["meshes"]) - 1)
        self.j["nodes"].append(n)
        self.j["scenes"][0]["nodes"].append(len(self.j["nodes"]) - 1)

    def write_gltf(self, name, data_uri=False):
        j = dict(self.j)
        if data_uri:
            j["buffers"] = [{"byteLength": len(self.bin),
                             "uri": "data:application/octet-stream;base64," + base64.b64encode(self.bin).decode()}]
        else:
            j["buffers"] = [{"byteLength": len(self.bin), "uri": name + ".bin"}]
            with open(os.path.join(OUT, name + ".bin"), "wb") as f:
                f.write(self.bin)
        with open(os.path.join(OUT, name + ".gltf"), "w") as f:
            json.dump(j, f, indent=1, sort_keys=True)
            f.write("\n")

    def write_glb(self, name):
        while len(self.bin) % 4:
            self.bin.append(0)
        j = dict(self.j)
        j["buffers"] = [{"byteLength": len(self.bin)}]
        js = json.dumps(j, sort_keys=True).encode()
        js += b" " * ((4 - len(js) % 4) % 4)
        body = struct.pack("<I", len(js)) + b"JSON" + js + struct.pack("<I", len(self.bin)) + b"BIN\x00" + self.bin
        with open(os.path.join(OUT, name + ".glb"), "wb") as f:
            f.write(struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body)


FLOAT, UBYTE, BYTE, USHORT, SHORT, UINT = 5126, 5121, 5120, 5123, 5122, 5125
QUAD_POS = [(-1.0, -1.0, 0.0), (1.0, -1.0, 0.0), (1.0, 1.0, 0.0), (-1.0, 1.0, 0.0)]
QUAD_UV = [(0.0, 1.0), (1.0, 1.0), (1.0, 0.0), (0.0, 0.0)]
QUAD_IDX = [0, 1, 2, 0, 2, 3]


def textured_quad(image, uvs=QUAD_UV):
    """A 2 x 2 m quad with the checker as its base colour; `image` adds the image entry."""
    d = Doc()
    pos = d.accessor("fff", QUAD_POS, FLOAT, "VEC3", minmax=True, target=34962)
    uv = d.accessor("ff", uvs, FLOAT, "VEC2", target=34962)
    idx = d.accessor("H", QUAD_IDX, USHORT, "SCALAR", target=34963)
    d.j["images"] = [image(d)]
    d.j["textures"] = [{"source": 0}]
    d.j["materials"] = [{"name": "checker", "pbrMetallicRoughness": {
        "baseColorTexture": {"index": 0}, "metallicFactor": 0.0, "roughnessFactor": 1.0}}]
    d.mesh_node([{"attributes": {"POSITION": pos, "TEXCOORD_0": uv}, "indices": idx, "material": 0}], "quad")
    return d


def add_corner_sun(d):
    """The sun of the corner files (occlusion-gi-*, alpha-*-gi): a directional light of 3 lux, its
    -Z turned 50 degrees down about x and 20 about y, so it lights the wall and the floor."""
    d.j["nodes"].append({"name": "sun", "rotation": [-0.4162, 0.1574, 0.0734, 0.8925],
                         "extensions": {"KHR_lights_punctual": {"light": 0}}})
    d.j["scenes"][0]["nodes"].append(len(d.j["nodes"]) - 1)
    d.j["extensionsUsed"] = ["KHR_lights_punctual"]
    d.j["extensions"] = {"KHR_lights_punctual": {"lights": [{"type": "directional", "intensity": 3.0}]}}


def main():
    os.makedirs(OUT, exist_ok=True)

    # Images inside the file: a GLB binary chunk, and a base64 data: uri (buffer too).
    textured_quad(lambda d: {"bufferView": d.view(CHECKER), "mimeType": "image/png"}).write_glb("texture-glb")
    textured_quad(lambda d: {"uri": "data:image/png;base64," + base64.b64encode(CHECKER).decode()}).write_gltf(
        "texture-data-uri", data_uri=True)
    # A KTX2 container (KHR_texture_basisu's format) in a chunk: refused by name.
    ktx2 = b"\xabKTX 20\xbb\r\n\x1a\n" + bytes(68)
    textured_quad(lambda d: {"bufferView": d.view(ktx2), "mimeType": "image/ktx2"}).write_glb("texture-ktx2")

    # Sparse accessors (§3.6.2.3): a triangle whose vertex 1 moves from (1,0,0) to (2,0,0); and one
    # with no base data at all (zeros) whose vertices 1 and 2 are set.
    d = Doc()
    pos = d.accessor("fff", [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)], FLOAT, "VEC3")
    d.j["accessors"][pos]["sparse"] = {"count": 1,
                                       "indices": {"bufferView": d.view(struct.pack("<H", 1)), "componentType": USHORT},
                                       "values": {"bufferView": d.view(struct.pack("<fff", 2.0, 0.0, 0.0))}}
    d.j["accessors"][pos]["min"], d.j["accessors"][pos]["max"] = [0, 0, 0], [2, 1, 0]
    d.mesh_node([{"attributes": {"POSITION": pos}}], "moved")
    d.write_gltf("sparse")
    d = Doc()
    d.j["accessors"].append({"componentType": FLOAT, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0],
                             "sparse": {"count": 2,
                                        "indices": {"bufferView": d.view(bytes([1, 2])), "componentType": UBYTE},
                                        "values": {"bufferView": d.view(struct.pack("<6f", 1, 0, 0, 0, 1, 0))}}})
    d.mesh_node([{"attributes": {"POSITION": 0}}], "from-zeros")
    d.write_gltf("sparse-zeros")

    # KHR_mesh_quantization: positions as unnormalized unsigned shorts in millimetres (a node scale
    # of 0.001 makes metres), normals as normalized bytes, UVs as normalized unsigned shorts.
    d = Doc()
    pos = d.accessor("HHH", [(0, 0, 0), (1000, 0, 0), (0, 1000, 0)], USHORT, "VEC3", minmax=True)
    nrm = d.accessor("bbbx", [(0, 0, 127)] * 3, BYTE, "VEC3", normalized=True)
    d.j["bufferViews"][d.j["accessors"][nrm]["bufferView"]]["byteStride"] = 4
    uv = d.accessor("HH", [(0, 65535), (65535, 65535), (0, 0)], USHORT, "VEC2", normalized=True)
    d.mesh_node([{"attributes": {"POSITION": pos, "NORMAL": nrm, "TEXCOORD_0": uv}}], "millimetres",
                scale=[0.001, 0.001, 0.001])
    d.j["extensionsUsed"] = d.j["extensionsRequired"] = ["KHR_mesh_quantization"]
    d.write_gltf("quantized")
    # The same integer positions without the extension: refused, naming it.
    d.j.pop("extensionsUsed"), d.j.pop("extensionsRequired")
    d.write_gltf("quantized-undeclared")

    # Triangle strip (mode 5) of 4 vertices: triangles (0,1,2) and (2,1,3), both facing +z; triangle
    # fan (mode 6) of 5 vertices around vertex 0: (0,1,2), (0,2,3), (0,3,4).
    d = Doc()
    pos = d.accessor("fff", [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (1.0, 1.0, 0.0)], FLOAT, "VEC3",
                     minmax=True)
    d.mesh_node([{"attributes": {"POSITION": pos}, "mode": 5}], "strip")
    d.write_gltf("strip")
    d = Doc()
    fan = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 1.0, 0.0), (0.0, 1.0, 0.0), (-1.0, 1.0, 0.0)]
    pos = d.accessor("fff", fan, FLOAT, "VEC3", minmax=True)
    idx = d.accessor("I", [0, 1, 2, 3, 4], UINT, "SCALAR")
    d.mesh_node([{"attributes": {"POSITION": pos}, "indices": idx, "mode": 6}], "fan")
    d.write_gltf("fan")

    # A mesh with a LINES primitive beside a triangle: the file loads, the lines are not drawn.
    d = Doc()
    pos = d.accessor("fff", [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)], FLOAT, "VEC3", minmax=True)
    d.mesh_node([{"attributes": {"POSITION": pos}, "mode": 1}, {"attributes": {"POSITION": pos}}], "lines-and-tri")
    d.write_gltf("lines")

    # Cameras: an orthographic camera node first, a perspective one second: the perspective one is
    # the view. And a light (KHR_lights_punctual), so this file is not given the studio.
    d = Doc()
    pos = d.accessor("fff", QUAD_POS, FLOAT, "VEC3", minmax=True)
    idx = d.accessor("H", QUAD_IDX, USHORT, "SCALAR")
    d.mesh_node([{"attributes": {"POSITION": pos}, "indices": idx}], "quad")
    d.j["cameras"] = [{"type": "orthographic", "orthographic": {"xmag": 2, "ymag": 2, "znear": 0.1, "zfar": 10}},
                      {"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1, "zfar": 20}}]
    d.j["nodes"] += [{"name": "ortho", "camera": 0, "translation": [0, 0, 3]},
                     {"name": "persp", "camera": 1, "translation": [0, 0, 4]},
                     {"name": "sun", "rotation": [0, 0, 0, 1],
                      "extensions": {"KHR_lights_punctual": {"light": 0}}}]
    d.j["scenes"][0]["nodes"] += [1, 2, 3]
    d.j["extensionsUsed"] = ["KHR_lights_punctual", "KHR_materials_clearcoat"]
    d.j["extensions"] = {"KHR_lights_punctual": {"lights": [{"type": "directional", "intensity": 2.0}]}}
    d.write_gltf("cameras")

    # Emissive texture: the checker glows (emissiveFactor 1 x texture x strength 4); no light, but
    # an emitter, so no studio. Drawn flat white before the texture was read.
    d = textured_quad(lambda d: {"bufferView": d.view(CHECKER), "mimeType": "image/png"})
    mat = d.j["materials"][0]
    mat["pbrMetallicRoughness"] = {"baseColorFactor": [0.5, 0.5, 0.5, 1.0], "metallicFactor": 0.0}
    mat["emissiveFactor"] = [1.0, 1.0, 1.0]
    mat["emissiveTexture"] = {"index": 0}
    mat["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": 4.0}}
    d.j["extensionsUsed"] = ["KHR_materials_emissive_strength"]
    d.write_glb("emissive-texture")

    # Vertex colours (COLOR_0, normalized unsigned bytes, RGBA): red, green, blue, white corners.
    d = Doc()
    pos = d.accessor("fff", QUAD_POS, FLOAT, "VEC3", minmax=True)
    col = d.accessor("BBBB", [(255, 0, 0, 255), (0, 255, 0, 255), (0, 0, 255, 255), (255, 255, 255, 255)], UBYTE,
                     "VEC4", normalized=True)
    idx = d.accessor("H", QUAD_IDX, USHORT, "SCALAR")
    d.j["materials"] = [{"name": "vertex-coloured", "pbrMetallicRoughness": {"metallicFactor": 0.0}}]
    d.mesh_node([{"attributes": {"POSITION": pos, "COLOR_0": col}, "indices": idx, "material": 0}], "quad")
    d.write_gltf("vertex-colors")

    # A real PBR material: metallicFactor 1 (the default) with the true metalness in the texture's
    # B channel, here 0 everywhere (roughness G = 1): a dielectric, so the GI methods apply to it.
    dielectric_mr = png_rgb(2, 2, [[(0, 255, 0), (0, 255, 0)], [(0, 255, 0), (0, 255, 0)]])
    d = textured_quad(lambda d: {"bufferView": d.view(CHECKER), "mimeType": "image/png"})
    d.j["images"].append({"bufferView": d.view(dielectric_mr), "mimeType": "image/png"})
    d.j["textures"].append({"source": 1})
    d.j["materials"][0]["pbrMetallicRoughness"] = {"baseColorTexture": {"index": 0},
                                                   "metallicRoughnessTexture": {"index": 1}}
    d.write_glb("metallic-texture")

    # A normal map: every texel tilts the normal 37 degrees toward +u (tangent space (0.6, 0, 0.8),
    # RGB (204, 128, 230)) on a white quad lit by the studio; no TANGENT, so both renderers use
    # the generated one (+x here). And the same quad with the map's tilt toward +v (green).
    for name, rgb in (("normal-map", (204, 128, 230)), ("normal-map-v", (128, 204, 230))):
        tilt = png_rgb(2, 2, [[rgb, rgb], [rgb, rgb]])
        d = textured_quad(lambda d: {"bufferView": d.view(tilt), "mimeType": "image/png"})
        d.j["materials"][0] = {"name": "tilted", "normalTexture": {"index": 0},
                               "pbrMetallicRoughness": {"metallicFactor": 0.0}}
        d.write_glb(name)

    # Samplers (glTF 5.26): the checker on a quad whose UVs run from -1 to 2 (three periods each
    # way), wrapS CLAMP_TO_EDGE, wrapT MIRRORED_REPEAT, NEAREST filtering: every texel a sharp
    # square, the edge texels stretched along u, the rows mirrored along v. And a sampler with a
    # wrap mode glTF does not have: refused naming the sampler and the key.
    wide_uv = [(3.0 * u - 1.0, 3.0 * v - 1.0) for u, v in QUAD_UV]
    d = textured_quad(lambda d: {"bufferView": d.view(CHECKER), "mimeType": "image/png"}, wide_uv)
    d.j["samplers"] = [{"wrapS": 33071, "wrapT": 33648, "magFilter": 9728, "minFilter": 9728}]
    d.j["textures"][0]["sampler"] = 0
    d.write_glb("sampler-wrap")
    d.j["samplers"][0]["wrapS"] = 10241
    d.write_glb("sampler-bad-wrap")

    # KHR_texture_transform on the base colour: offset (0.5, 1), rotation pi/2, scale (2, 1), so
    # uv' = (v + 0.5, 1 - 2u): the checker turned a quarter, stretched and shifted.
    d = textured_quad(lambda d: {"bufferView": d.view(CHECKER), "mimeType": "image/png"})
    d.j["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] = {
        "KHR_texture_transform": {"offset": [0.5, 1.0], "rotation": math.pi / 2, "scale": [2.0, 1.0]}}
    d.j["extensionsUsed"] = ["KHR_texture_transform"]
    d.write_glb("texture-transform")
    # TEXCOORD_1: the base colour reads the second set (texCoord 1, the checker's own UVs) while
    # TEXCOORD_0 is (0, 0) everywhere (one red texel): a renderer reading set 0 draws it all red.
    d = Doc()
    pos = d.accessor("fff", QUAD_POS, FLOAT, "VEC3", minmax=True, target=34962)
    uv0 = d.accessor("ff", [(0.0, 0.0)] * 4, FLOAT, "VEC2", target=34962)
    uv1 = d.accessor("ff", QUAD_UV, FLOAT, "VEC2", target=34962)
    idx = d.accessor("H", QUAD_IDX, USHORT, "SCALAR", target=34963)
    d.j["images"] = [{"bufferView": d.view(CHECKER), "mimeType": "image/png"}]
    d.j["textures"] = [{"source": 0}]
    d.j["materials"] = [{"name": "second-set", "pbrMetallicRoughness": {
        "baseColorTexture": {"index": 0, "texCoord": 1}, "metallicFactor": 0.0, "roughnessFactor": 1.0}}]
    d.mesh_node([{"attributes": {"POSITION": pos, "TEXCOORD_0": uv0, "TEXCOORD_1": uv1}, "indices": idx,
                  "material": 0}], "quad")
    d.write_glb("texcoord1")

    # alphaMode MASK: a white quad whose 2 x 2 texture is opaque on one diagonal (alpha 255: top
    # left, bottom right) and clear on the other (alpha 0), cutoff 0.5, held 0.5 m in front of a grey
    # 3 x 3 m wall: the camera sees the wall through the holes, and the studio's key light casts a
    # shadow with holes on it. The same with alphaMode OPAQUE is the control (no holes).
    holes = png_rgba(2, 2, [[(255, 255, 255, 255), (255, 255, 255, 0)], [(255, 255, 255, 0), (255, 255, 255, 255)]])
    for name, mode in (("alpha-mask", "MASK"), ("alpha-opaque", "OPAQUE")):
        d = textured_quad(lambda d: {"bufferView": d.view(holes), "mimeType": "image/png"})
        d.j["nodes"][0]["translation"] = [0.0, 0.0, 0.5]
        d.j["materials"][0]["alphaMode"] = mode
        if mode == "MASK":
            d.j["materials"][0]["alphaCutoff"] = 0.5
        wall = d.accessor("fff", [(3 * x, 3 * y, z) for x, y, z in QUAD_POS], FLOAT, "VEC3", minmax=True)
        widx = d.accessor("H", QUAD_IDX, USHORT, "SCALAR")
        d.j["materials"].append({"name": "wall", "pbrMetallicRoughness": {
            "baseColorFactor": [0.5, 0.5, 0.5, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}})
        d.mesh_node([{"attributes": {"POSITION": wall}, "indices": widx, "material": 1}], "wall")
        d.write_glb(name)

    # doubleSided: a red quad 0.5 m in front of a grey 3 x 3 m wall, turned to show the camera (on
    # +z) its back face (winding reversed: its front faces -z, the wall). Single-sided, the camera
    # sees the wall through it (culled in the G-buffer, passed by the tracer's camera rays); double-
    # sided it hides the wall. Either way it casts the studio key light's shadow on the wall.
    # single-sided-mirrored: the single-sided quad on a node scaled (-1, 1, 1) (the quad is symmetric
    # in x, so it stays where it was). The mirror reverses its triangles' winding, and glTF 2.0 3.7.2.1
    # makes a mirrored node's front faces clockwise: its front still faces the wall (the mirror of -z
    # in x is -z), so both renderers show the wall as for single-sided.glb. A renderer that judges
    # the winding without the determinant shows the red quad instead, as for double-sided.glb.
    for name, both, mirror in (("single-sided", False, False), ("double-sided", True, False),
                               ("single-sided-mirrored", False, True)):
        d = Doc()
        pos = d.accessor("fff", QUAD_POS, FLOAT, "VEC3", minmax=True)
        idx = d.accessor("H", [0, 2, 1, 0, 3, 2], USHORT, "SCALAR")
        d.j["materials"] = [{"name": "red-back", "doubleSided": both, "pbrMetallicRoughness": {
            "baseColorFactor": [0.8, 0.1, 0.1, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}},
            {"name": "wall", "pbrMetallicRoughness": {
                "baseColorFactor": [0.5, 0.5, 0.5, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}}]
        d.mesh_node([{"attributes": {"POSITION": pos}, "indices": idx, "material": 0}], "quad",
                    translation=[0.0, 0.0, 0.5], **({"scale": [-1.0, 1.0, 1.0]} if mirror else {}))
        wall = d.accessor("fff", [(3 * x, 3 * y, z) for x, y, z in QUAD_POS], FLOAT, "VEC3", minmax=True)
        widx = d.accessor("H", QUAD_IDX, USHORT, "SCALAR")
        d.mesh_node([{"attributes": {"POSITION": wall}, "indices": widx, "material": 1}], "wall")
        d.write_glb(name)

    # occlusionTexture: a Lambertian (specularFactor 0) quad of albedo 0.5 filling the view of a
    # camera 1 m in front of it, under a uniform 1-nit sky (uniform-sky.pfm: the environment's split
    # finds no light brighter than the mean, so all of it is the rasterizer's ambient): the tracer
    # gives 0.5 nits everywhere (it ignores the texture). With an occlusion texture of grey 128
    # (0.502, data) the rasterizer's ambient-only image is 0.502 of the untextured one; with
    # strength 0 it is the same.
    sky_w, sky_h = 8, 4
    with open(os.path.join(OUT, "uniform-sky.pfm"), "wb") as f:
        f.write(b"PF\n%d %d\n-1.0\n" % (sky_w, sky_h) + struct.pack("<%df" % (3 * sky_w * sky_h),
                                                                       *([1.0] * (3 * sky_w * sky_h))))
    grey = png_rgb(2, 2, [[(128, 128, 128), (128, 128, 128)], [(128, 128, 128), (128, 128, 128)]])
    for name, strength in (("occlusion-none", None), ("occlusion-half", 1.0), ("occlusion-strength0", 0.0)):
        d = Doc()
        pos = d.accessor("fff", QUAD_POS, FLOAT, "VEC3", minmax=True)
        uv = d.accessor("ff", QUAD_UV, FLOAT, "VEC2")
        idx = d.accessor("H", QUAD_IDX, USHORT, "SCALAR")
        mat = {"name": "occluded", "pbrMetallicRoughness": {
            "baseColorFactor": [0.5, 0.5, 0.5, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0},
            "extensions": {"KHR_materials_specular": {"specularFactor": 0.0}}}
        if strength is not None:
            d.j["images"] = [{"bufferView": d.view(grey), "mimeType": "image/png"}]
            d.j["textures"] = [{"source": 0}]
            mat["occlusionTexture"] = {"index": 0, "strength": strength}
        d.j["materials"] = [mat]
        d.j["extensionsUsed"] = ["KHR_materials_specular"]
        d.mesh_node([{"attributes": {"POSITION": pos, "TEXCOORD_0": uv}, "indices": idx, "material": 0}], "quad")
        d.j["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.05, "zfar": 10}}]
        d.j["nodes"].append({"name": "view", "camera": 0, "translation": [0, 0, 1]})
        d.j["scenes"][0]["nodes"].append(1)
        d.j["scenes"][0]["extras"] = {"gikiosk": {"environment": {"uri": "uniform-sky.pfm"}}}
        d.write_glb(name)

    # occlusionTexture on the GI methods' light: a white wall and floor meeting at a right angle, lit
    # by a sun from above and in front (no environment: no ambient), both with the grey occlusion
    # texture or neither. Direct light is the same in both files; what a GI method adds (its
    # bounce between the two) is 0.502 as much with the texture.
    for name, occluded in (("occlusion-gi-none", False), ("occlusion-gi-half", True)):
        d = Doc()
        wall = d.accessor("fff", QUAD_POS, FLOAT, "VEC3", minmax=True)
        floor = d.accessor("fff", [(x, -1.0, 1.0 - y) for x, y, _ in QUAD_POS], FLOAT, "VEC3", minmax=True)
        uv = d.accessor("ff", QUAD_UV, FLOAT, "VEC2")
        idx = d.accessor("H", QUAD_IDX, USHORT, "SCALAR")
        mat = {"name": "white", "pbrMetallicRoughness": {
            "baseColorFactor": [0.8, 0.8, 0.8, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}}
        if occluded:
            d.j["images"] = [{"bufferView": d.view(grey), "mimeType": "image/png"}]
            d.j["textures"] = [{"source": 0}]
            mat["occlusionTexture"] = {"index": 0}
        d.j["materials"] = [mat]
        d.mesh_node([{"attributes": {"POSITION": wall, "TEXCOORD_0": uv}, "indices": idx, "material": 0},
                     {"attributes": {"POSITION": floor, "TEXCOORD_0": uv}, "indices": idx, "material": 0}],
                    "corner")
        add_corner_sun(d)
        d.write_glb(name)

    # alphaMode MASK on the GI methods' light: occlusion-gi-none's white corner under its sun, and
    # the holes quad of alpha-mask.glb (red, double-sided) held level 0.8 m above the floor
    # between the sun and the floor. Through the holes the sun reaches the white floor, whose
    # bounce lights the wall white; solid (the control, alphaMode OPAQUE), the quad shades the
    # floor and its lit top bleeds twice as much red onto the wall. A GI method whose own scene
    # pass (RSM, voxels) sees the quad solid gives the masked file the control's indirect light.
    for name, mode in (("alpha-mask-gi", "MASK"), ("alpha-opaque-gi", "OPAQUE")):
        d = Doc()
        wall = d.accessor("fff", QUAD_POS, FLOAT, "VEC3", minmax=True)
        floor = d.accessor("fff", [(x, -1.0, 1.0 - y) for x, y, _ in QUAD_POS], FLOAT, "VEC3", minmax=True)
        shade = d.accessor("fff", [(x, -0.2, 1.0 - 0.6 * y) for x, y, _ in QUAD_POS], FLOAT, "VEC3", minmax=True)
        uv = d.accessor("ff", QUAD_UV, FLOAT, "VEC2")
        idx = d.accessor("H", QUAD_IDX, USHORT, "SCALAR")
        d.j["images"] = [{"bufferView": d.view(holes), "mimeType": "image/png"}]
        d.j["textures"] = [{"source": 0}]
        cut = {"name": "holes", "doubleSided": True, "alphaMode": mode, "pbrMetallicRoughness": {
            "baseColorFactor": [0.9, 0.1, 0.1, 1.0], "baseColorTexture": {"index": 0},
            "metallicFactor": 0.0, "roughnessFactor": 1.0}}
        if mode == "MASK":
            cut["alphaCutoff"] = 0.5
        d.j["materials"] = [{"name": "white", "pbrMetallicRoughness": {
            "baseColorFactor": [0.8, 0.8, 0.8, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}}, cut]
        d.mesh_node([{"attributes": {"POSITION": wall}, "indices": idx, "material": 0},
                     {"attributes": {"POSITION": floor}, "indices": idx, "material": 0},
                     {"attributes": {"POSITION": shade, "TEXCOORD_0": uv}, "indices": idx, "material": 1}],
                    "corner")
        add_corner_sun(d)
        d.write_glb(name)

    # alphaMode BLEND: a red quad of alpha 0.5 (base colour factor) 0.5 m in front of a white wall,
    # both Lambertian (specularFactor 0), the camera 0.5 m in front of the quad (it fills the view),
    # under the uniform 1-nit sky (ambient only). The same quad OPAQUE, and MASKed away (cutoff 0.6
    # over alpha 0.5: not there), give the two colours the blend mixes half and half.
    for name, mode in (("blend-half", "BLEND"), ("blend-opaque", "OPAQUE"), ("blend-cut", "MASK")):
        d = Doc()
        pos = d.accessor("fff", QUAD_POS, FLOAT, "VEC3", minmax=True)
        idx = d.accessor("H", QUAD_IDX, USHORT, "SCALAR")
        lambert = {"KHR_materials_specular": {"specularFactor": 0.0}}
        red = {"name": "red", "alphaMode": mode, "extensions": lambert, "pbrMetallicRoughness": {
            "baseColorFactor": [1.0, 0.0, 0.0, 0.5], "metallicFactor": 0.0, "roughnessFactor": 1.0}}
        if mode == "MASK":
            red["alphaCutoff"] = 0.6
        d.j["materials"] = [red, {"name": "white", "extensions": lambert, "pbrMetallicRoughness": {
            "baseColorFactor": [0.8, 0.8, 0.8, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}}]
        d.j["extensionsUsed"] = ["KHR_materials_specular"]
        d.mesh_node([{"attributes": {"POSITION": pos}, "indices": idx, "material": 0}], "quad",
                    translation=[0.0, 0.0, 0.5])
        wall = d.accessor("fff", [(3 * x, 3 * y, z) for x, y, z in QUAD_POS], FLOAT, "VEC3", minmax=True)
        d.mesh_node([{"attributes": {"POSITION": wall}, "indices": idx, "material": 1}], "wall")
        d.j["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.05, "zfar": 10}}]
        d.j["nodes"].append({"name": "view", "camera": 0, "translation": [0, 0, 1]})
        d.j["scenes"][0]["nodes"].append(2)
        d.j["scenes"][0]["extras"] = {"gikiosk": {"environment": {"uri": "uniform-sky.pfm"}}}
        d.write_glb(name)

    # alphaMode BLEND on the checker (counted in `gltf reads:`); refusals: a texture on
    # TEXCOORD_2, a transform whose scale is not two numbers, an alphaMode glTF does not have.
    for name, change in (
            ("alpha-blend", lambda m: m.update(alphaMode="BLEND")),
            ("texcoord2", lambda m: m["pbrMetallicRoughness"]["baseColorTexture"].update(texCoord=2)),
            ("texture-transform-bad", lambda m: m["pbrMetallicRoughness"]["baseColorTexture"].update(
                extensions={"KHR_texture_transform": {"scale": [2.0]}})),
            ("alpha-bad-mode", lambda m: m.update(alphaMode="CUTOUT"))):
        d = textured_quad(lambda d: {"bufferView": d.view(CHECKER), "mimeType": "image/png"})
        change(d.j["materials"][0])
        if name == "texture-transform-bad":
            d.j["extensionsUsed"] = ["KHR_texture_transform"]
        d.write_glb(name)

    # Extensions: one required that gikiosk does not read (GPU instancing), refused by name. (Draco
    # and meshopt are read: tests/unit/test_gltf_draco.c and test_gltf_meshopt.c encode their
    # streams with the C libraries, which Python lacks here.)
    d = Doc()
    pos = d.accessor("fff", [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)], FLOAT, "VEC3", minmax=True)
    d.mesh_node([{"attributes": {"POSITION": pos}}], "tri")
    d.j["extensionsUsed"] = d.j["extensionsRequired"] = ["EXT_mesh_gpu_instancing"]
    d.write_gltf("requires-instancing")


if __name__ == "__main__":
    main()
