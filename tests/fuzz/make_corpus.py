#!/usr/bin/env python3
"""Writes the small seed inputs under corpus/<target>/ (run once; the files are committed). Each is a
well-formed file of a few particles in one of the layouts the reader accepts (headers documented in
sim/io/*.h), so the fuzzer starts from inputs that reach deep into the parser."""
import base64, gzip, json, os, struct, zlib

HERE = os.path.dirname(os.path.abspath(__file__))
P = [(0.0, 0.0, 0.0), (0.04, 0.0, 0.0), (0.0, 0.04, 0.0), (0.04, 0.04, 0.04)]
V = [(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0), (0.5, 0.5, 0.5)]


def put(target, name, data):
    os.makedirs(os.path.join(HERE, 'corpus', target), exist_ok=True)
    with open(os.path.join(HERE, 'corpus', target, name), 'wb') as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def bgeo(attrs):
    """attrs: list of (name, type, size, per-point values); type 0 float, 1 int, 5 vector."""
    b = b'BgeoV' + struct.pack('>i', 5) + struct.pack('>7i', len(P), 0, 0, 0, len(attrs), 0, 0) + struct.pack('>i', 0)
    for name, typ, size, _ in attrs:
        b += struct.pack('>h', len(name)) + name.encode() + struct.pack('>Hi', size, typ) + b'\0' * (4 * size)
    for i, p in enumerate(P):
        b += struct.pack('>4f', *p, 1.0)
        for _, typ, size, values in attrs:
            b += struct.pack('>%d%s' % (size, 'i' if typ == 1 else 'f'), *values[i])
    return b + b'\x00\xff'


fluid = bgeo([('v', 5, 3, V), ('id', 1, 1, [(i,) for i in range(4)]), ('mass', 0, 1, [(0.064,)] * 4)])
put('bgeo', 'fluid.bgeo', fluid)
put('bgeo', 'fluid.bgeo.gz', gzip.compress(fluid, mtime=0))
put('bgeo', 'positions_only.bgeo', bgeo([]))
put('bgeo', 'diffuse.bgeo', bgeo([('v', 5, 3, V), ('type', 1, 1, [(i % 3,) for i in range(4)]),
                                   ('lifetime', 0, 1, [(2.0,)] * 4), ('id', 1, 1, [(i,) for i in range(4)]),
                                   ('birth', 1, 1, [(3,)] * 4), ('sample', 1, 1, [(0,)] * 4)]))

pts = ' '.join('%g %g %g' % p for p in P)
vel = ' '.join('%g %g %g' % v for v in V)
put('vtk', 'ascii_polydata.vtk', '# vtk DataFile Version 3.0\nparticles\nASCII\nDATASET POLYDATA\n'
    'FIELD FieldData 1\nTIME 1 1 double\n0.5\n'
    f'POINTS 4 float\n{pts}\nVERTICES 4 8\n1 0\n1 1\n1 2\n1 3\n'
    f'POINT_DATA 4\nSCALARS id int 1\nLOOKUP_TABLE default\n0 1 2 3\nVECTORS velocity float\n{vel}\n')
binary = b''.join(struct.pack('>3f', *p) for p in P)
binv = b''.join(struct.pack('>3f', *v) for v in V)
put('vtk', 'binary_ugrid.vtk', b'# vtk DataFile Version 4.2\nSPlisHSPlasH\nBINARY\nDATASET UNSTRUCTURED_GRID\n'
    b'POINTS 4 float\n' + binary + b'\nCELLS 4 8\n' + b''.join(struct.pack('>2i', 1, i) for i in range(4)) +
    b'\nCELL_TYPES 4\n' + struct.pack('>4i', 1, 1, 1, 1) + b'\nPOINT_DATA 4\nFIELD FieldData 2\n'
    b'id 1 4 unsigned_int\n' + struct.pack('>4I', 0, 1, 2, 3) + b'\nvelocity 3 4 float\n' + binv + b'\n')


def b64_block(raw, compress):
    if compress:
        c = zlib.compress(raw)
        return base64.b64encode(struct.pack('<4I', 1, len(raw), len(raw), len(c))).decode() + base64.b64encode(c).decode()
    return base64.b64encode(struct.pack('<I', len(raw)) + raw).decode()


def vtu(fmt, compress=False):
    head = '<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian"' + \
           (' compressor="vtkZLibDataCompressor"' if compress else '') + '>\n<UnstructuredGrid><Piece NumberOfPoints="4" NumberOfCells="0">\n'
    lp = struct.pack('<12f', *sum(P, ()))
    lv = struct.pack('<12f', *sum(V, ()))
    li = struct.pack('<4I', 0, 1, 2, 3)
    if fmt == 'ascii':
        arrays = [('Points', 'Float32', 3, pts), ('velocity', 'Float32', 3, vel), ('id', 'UInt32', 1, '0 1 2 3')]
        body = ''.join(f'<{"Points" if n == "Points" else "PointData"}><DataArray type="{t}" Name="{n}" NumberOfComponents="{c}" format="ascii">{d}</DataArray></{"Points" if n == "Points" else "PointData"}>\n'
                       for n, t, c, d in arrays)
        return head + body + '</Piece></UnstructuredGrid></VTKFile>\n'
    if fmt == 'binary':
        d = lambda raw: b64_block(raw, compress)
        return head + f'<Points><DataArray type="Float32" NumberOfComponents="3" format="binary">{d(lp)}</DataArray></Points>\n' \
            f'<PointData><DataArray type="Float32" Name="velocity" NumberOfComponents="3" format="binary">{d(lv)}</DataArray>' \
            f'<DataArray type="UInt32" Name="id" format="binary">{d(li)}</DataArray></PointData>\n</Piece></UnstructuredGrid></VTKFile>\n'
    # appended raw: each block is a UInt32 byte count, then the bytes
    blocks, offsets, o = [lp, lv, li], [], 0
    for b in blocks:
        offsets.append(o)
        o += 4 + len(b)
    text = head + f'<Points><DataArray type="Float32" NumberOfComponents="3" format="appended" offset="{offsets[0]}"/></Points>\n' \
        f'<PointData><DataArray type="Float32" Name="velocity" NumberOfComponents="3" format="appended" offset="{offsets[1]}"/>' \
        f'<DataArray type="UInt32" Name="id" format="appended" offset="{offsets[2]}"/></PointData>\n</Piece></UnstructuredGrid>\n' \
        '<AppendedData encoding="raw">_'
    return text.encode() + b''.join(struct.pack('<I', len(b)) + b for b in blocks) + b'</AppendedData></VTKFile>\n'


put('vtu', 'ascii.vtu', vtu('ascii'))
put('vtu', 'base64.vtu', vtu('binary'))
put('vtu', 'zlib.vtu', vtu('binary', True))
put('vtu', 'appended_raw.vtu', vtu('appended'))

rows = '\n'.join('%g %g %g %g %g %g %d' % (*P[i], *V[i], i) for i in range(4))
props = 'property float x\nproperty float y\nproperty float z\nproperty float vx\nproperty float vy\nproperty float vz\nproperty uint id\n'
put('ply', 'ascii.ply', f'ply\nformat ascii 1.0\nelement vertex 4\n{props}element face 1\nproperty list uchar int vertex_indices\nend_header\n{rows}\n3 0 1 2\n')
for order, fmt in (('<', 'binary_little_endian'), ('>', 'binary_big_endian')):
    body = b''.join(struct.pack(order + '6fI', *P[i], *V[i], i) for i in range(4))
    put('ply', fmt + '.ply', f'ply\nformat {fmt} 1.0\nelement vertex 4\n{props}end_header\n'.encode() + body)


def with_crc(b):
    return b + struct.pack('<I', zlib.crc32(b) & 0xffffffff)


spf = b'SPUMEFL1' + struct.pack('<Iidf', 1, 3, 0.06, 0.02) + struct.pack('<QI', 4, 7) + struct.pack('<4I', 0, 1, 2, 3) + \
    struct.pack('<12f', *sum(P, ())) + struct.pack('<12f', *sum(V, ())) + struct.pack('<4f', *[0.064] * 4)
put('cache', 'fluid.spf', with_crc(spf))
put('cache', 'fluid_positions_only.spf', with_crc(b'SPUMEFL1' + struct.pack('<IidfQI', 1, 0, 0.0, 0.02, 4, 0) + struct.pack('<12f', *sum(P, ()))))
spd = b'SPUMEDF1' + struct.pack('<IidQ', 1, 3, 0.06, 4) + struct.pack('<3Q', 2, 1, 1) + struct.pack('<4Q', 1 << 32, 2 << 32, 3, 4) + \
    struct.pack('<12f', *sum(P, ())) + struct.pack('<12f', *sum(V, ())) + struct.pack('<4f', 1, 2, 3, 4) + bytes([0, 0, 1, 2])
put('cache', 'diffuse.spd', with_crc(spd))

scenes = {
    'minimal.json': {'fluid': {'files': 'cache/ParticleData_Fluid_%d.bgeo', 'radius': 0.02}},
    'full.json': {'name': 'wave', 'gravity': [0, -9.81, 0],
                  'fluid': {'files': 'f_####.vtk', 'radius': 0.01, 'support_radius': 0.04, 'fps': 60, 'rest_density': 998, 'frames': [0, 10]},
                  'solids': [{'type': 'tank', 'min': [0, 0, 0], 'max': [2, 1, 1], 'open_top': True},
                             {'type': 'box', 'min': [0.5, 0, 0.2], 'max': [0.7, 0.3, 0.4],
                              'motion': {'type': 'keyframes', 'times': [0, 1], 'offsets': [[0, 0, 0], [0.1, 0, 0]]}},
                             {'type': 'sphere', 'center': [1.5, 0.5, 0.5], 'radius': 0.1,
                              'motion': {'type': 'sine', 'axis': [1, 0, 0], 'amplitude': 0.1, 'frequency': 1}}],
                  'domain': {'min': [-1, -1, -1], 'max': [3, 3, 3]}, 'output': {'bgeo': True},
                  'diffuse': {'tau_ta': [2, 8], 'tau_wc': [2, 8], 'tau_k': [0.01, 0.2], 'k_ta': 1000, 'k_wc': 1000,
                              'lifetime': [1, 3], 'surface_threshold': 0.3, 'spray_below': 6, 'bubble_above': 20,
                              'hysteresis': 1, 'count_solids': True, 'buoyancy': 2, 'drag': 0.5, 'bubble_drag': 'paper',
                              'drag_reference_step': 0.02, 'spray_integrator': 'euler_cromer', 'foam_velocity': 'stale',
                              'substeps': 2, 'seed': 7, 'max_particles': 100000}},
    'solver.json': {'fluid': {'source': 'solver', 'radius': 0.01, 'blocks': [{'min': [0, 0, 0], 'max': [0.5, 1, 0.5]}],
                              'solver': {'viscosity': 1e-3, 'cfl': 0.4, 'min_dt': 1e-5, 'max_dt': 0.005, 'warm_start': False}},
                    'solids': [{'type': 'tank', 'min': [0, 0, 0], 'max': [2, 2, 1]}], 'output': {'fluid_bgeo': True}},
}
for name, scene in scenes.items():
    put('scene', name, json.dumps(scene, indent=1))
put('scene', 'comments.json', '// a scene\n{ /* block */ "fluid": {"files": "a_%d.ply", "radius": 2e-2}, "diffuse": {"seed": 1} }\n')
