#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""A second, independent reader of prtkit blobs written from formats/SPEC.md alone (no code shared
with the C reader), used as a cross-check: it validates a blob by the rules of SPEC.md §8 (quick
checks, checksums, padding, contents of uncompressed known kinds including the SHTR (§7.1), WVLT
(§7.2), PSTR (§7.3), CLTH (§7.4), SFLD (§7.5) and SCNE (§7.6) layouts; zstd frames are not decoded, the standard library has no zstd) and
prints the section table and the technique headers. It also holds a blob to the rules SPEC.md
states for writers where a reader need not check them (PSTR: every vertex's weights sum to 65535,
or are all 0), since what it reads are the writer's golden blobs; such failures say "WRITER".

usage: spec_reader.py FILE.prtk   -> exit 0 if valid, 1 with the failed rule otherwise
"""
import math
import struct
import sys

# (tag, layout version) -> element size; None = variable, the exact size is in the layout (§7).
KINDS = {(b"INFO", 1): 1, (b"VPOS", 1): 12, (b"VNRM", 1): 12, (b"VTAN", 1): 12, (b"TRIS", 1): 12,
         (b"SHTR", 1): None, (b"WVLT", 1): None, (b"PSTR", 1): None, (b"CLTH", 1): None,
         (b"SFLD", 1): None, (b"SCNE", 1): None}
# One element per VPOS vertex (§7 relations); CLTH counts its own domain and needs nothing, SFLD
# counts its own and needs VPOS and VNRM.
PER_VERTEX = (b"VNRM", b"VTAN", b"SHTR", b"WVLT", b"PSTR")


def crc32c(data, crc=0):
    """CRC-32C, bit by bit (SPEC.md §6)."""
    crc ^= 0xFFFFFFFF
    for byte in data:
        crc ^= byte
        for _ in range(8):
            crc = (crc >> 1) ^ 0x82F63B78 if crc & 1 else crc >> 1
    return crc ^ 0xFFFFFFFF


def align16(x):
    return (x + 15) & ~15


class Invalid(Exception):
    pass


def require(condition, rule):
    if not condition:
        raise Invalid(rule)


def finite(f):
    return f == f and f not in (float("inf"), float("-inf"))


def padded4(n):
    return (n + 3) & ~3


def read_shtr(data, vertex_count):
    """SHTR, SPEC.md §7.1: header fields, exact size, zero padding, finite offsets and scales >= 0."""
    require(len(data) >= 32, "CORRUPT: SHTR header")
    order, vertices, channels, bits, kind, bounces, r0, r1 = struct.unpack_from("<8I", data)
    require(1 <= order <= 16, "CORRUPT: SHTR order")
    require(channels in (1, 3), "CORRUPT: SHTR channels")
    require(bits in (8, 16), "CORRUPT: SHTR bits")
    require(r0 == 0 and r1 == 0, "CORRUPT: SHTR reserved")
    require(vertices == vertex_count, "CORRUPT: SHTR vertex count")
    coefficients = channels * order * order
    payload = 32 + 8 * coefficients + vertices * coefficients * (bits // 8)
    require(len(data) == padded4(payload), "CORRUPT: SHTR size")
    require(data[payload:] == bytes(len(data) - payload), "CORRUPT: SHTR padding")
    for j in range(coefficients):
        offset, scale = struct.unpack_from("<2f", data, 32 + 8 * j)
        require(finite(offset) and finite(scale), "NON_FINITE: SHTR offset or scale")
        require(scale >= 0, "CORRUPT: SHTR scale < 0")
    return dict(order=order, vertices=vertices, channels=channels, bits=bits, kind=kind,
                bounces=bounces)


def read_wvlt(data, vertex_count):
    """WVLT, SPEC.md §7.2: header fields, exact size, padding, scales, rows, blocks and pairs."""
    require(len(data) >= 32, "CORRUPT: WVLT header")
    (param, size, vertices, quantizer, keep, bounces, pairs,
     reserved) = struct.unpack_from("<8I", data)
    require(param in (0, 1), "CORRUPT: WVLT param")
    require(size in (16, 32, 64, 128), "CORRUPT: WVLT face size")
    require(quantizer in (0, 1), "CORRUPT: WVLT quantizer")
    require(reserved == 0, "CORRUPT: WVLT reserved")
    require(vertices == vertex_count, "CORRUPT: WVLT vertex count")
    faces = 6 if param == 0 else 2
    bands = faces * ((size.bit_length() - 1) + 1)  # F (log2 S + 1)
    blocks = faces * size * size // 256
    vertex_scale = 32 + 4 * bands
    row_start = vertex_scale + 12 * vertices
    counts = row_start + 4 * (vertices + 1)
    first_pair = counts + 2 * vertices * blocks
    payload = first_pair + 2 * pairs
    require(len(data) == padded4(payload), "CORRUPT: WVLT size")
    require(data[payload:] == bytes(len(data) - payload), "CORRUPT: WVLT padding")
    scales = struct.unpack_from(f"<{bands + 3 * vertices}f", data, 32)
    require(all(finite(x) for x in scales), "NON_FINITE: WVLT scale")
    require(all(x >= 0 for x in scales), "CORRUPT: WVLT scale < 0")
    starts = struct.unpack_from(f"<{vertices + 1}I", data, row_start)
    require(starts[0] == 0 and starts[vertices] == pairs, "CORRUPT: WVLT row starts")
    at = 0
    for v in range(vertices):
        require(starts[v] == at, "CORRUPT: WVLT row start is not the running sum")
        for n in struct.unpack_from(f"<{blocks}H", data, counts + 2 * v * blocks):
            require(n <= 256 and at + n <= pairs, "CORRUPT: WVLT block count")
            block = data[first_pair + 2 * at:first_pair + 2 * (at + n)]
            indices, values = block[0::2], block[1::2]
            require(all(a < b for a, b in zip(indices, indices[1:])),
                    "CORRUPT: WVLT indices not increasing")
            require(all(q not in (0, 0x80) for q in values), "CORRUPT: WVLT value 0 or -128")
            at += n
    require(starts[vertices] == at, "CORRUPT: WVLT row start is not the running sum")
    return dict(param=param, size=size, vertices=vertices, quantizer=quantizer, keep=keep,
                bounces=bounces, pairs=pairs)


def read_pstr(data, vertex_count):
    """PSTR, SPEC.md §7.3: header fields, exact size, padding, parents, evaluation order, finite
    floats, basis scales >= 0, range min <= max, skin joint indices < J; and the writers' rule that
    each vertex's weights sum to 65535 (or are all 0)."""
    require(len(data) >= 64, "CORRUPT: PSTR header")
    (order, vertices, joints, pose_dims, basis_dims, model, bits, model_joint, kind,
     bounces) = struct.unpack_from("<10I", data)
    (albedo,) = struct.unpack_from("<f", data, 40)
    (flags,) = struct.unpack_from("<I", data, 44)
    # In the order of the §7.3 table, the vertex count last.
    require(1 <= order <= 8, "CORRUPT: PSTR order")
    require(1 <= joints <= 256, "CORRUPT: PSTR joint count")
    features = 3 * joints
    require(pose_dims <= features, "CORRUPT: PSTR pose_dims")
    require(1 <= basis_dims <= 256, "CORRUPT: PSTR basis_dims")
    require(model in (0, 1), "CORRUPT: PSTR model")
    require(bits in (8, 16), "CORRUPT: PSTR bits")
    require(model_joint < joints, "CORRUPT: PSTR model_joint")
    require(finite(albedo), "NON_FINITE: PSTR albedo")
    require(albedo >= 0, "CORRUPT: PSTR albedo < 0")
    require(flags & ~1 == 0, "CORRUPT: PSTR flags")
    require(data[48:64] == bytes(16), "CORRUPT: PSTR reserved")
    require(vertices == vertex_count, "CORRUPT: PSTR vertex count")

    # The parts in the order of the §7.3 table, each size from the header.
    coefficients, value_size = order * order, bits // 8
    values_bytes = vertices * basis_dims * value_size
    at, parts = 64, {}
    for name, part_size in (("joints", 140 * joints), ("eval_order", 4 * joints),
                            ("pose_mean", 4 * features), ("pose_basis", 4 * features * pose_dims),
                            ("pose_range", 8 * pose_dims),
                            ("regression", 4 * (pose_dims + 1) * basis_dims * coefficients),
                            ("basis_params", 8 * basis_dims),
                            ("basis_values", padded4(values_bytes)),
                            ("skin", 36 * vertices)):
        parts[name] = at
        at += part_size
    # The sum of the parts is the raw_size formula of §7.3.
    require(at == 64 + 144 * joints + 4 * features + 4 * features * pose_dims + 8 * pose_dims
            + 4 * (pose_dims + 1) * basis_dims * coefficients + 8 * basis_dims
            + padded4(values_bytes) + 36 * vertices, "CORRUPT: PSTR parts do not add up")
    require(len(data) == at, "CORRUPT: PSTR size")
    values_end = parts["basis_values"] + values_bytes
    require(data[values_end:parts["skin"]] == bytes(parts["skin"] - values_end),
            "CORRUPT: PSTR padding")

    # Parents: -1, or a joint < J other than itself (not necessarily a lower index); the model
    # joint's parent is -1.
    parents = []
    for j in range(joints):
        (parent,) = struct.unpack_from("<i", data, parts["joints"] + 140 * j)
        require(parent == -1 or 0 <= parent < joints and parent != j,
                f"CORRUPT: PSTR joint {j} parent {parent}")
        require(j != model_joint or parent == -1, "CORRUPT: PSTR model joint has a parent")
        parents.append(parent)
    # Evaluation order: every joint once, each after its parent (this also rules out cycles).
    placed = set()
    for joint in struct.unpack_from(f"<{joints}I", data, parts["eval_order"]):
        require(joint < joints and joint not in placed,
                "CORRUPT: PSTR eval_order is not a permutation")
        require(parents[joint] == -1 or parents[joint] in placed,
                f"CORRUPT: PSTR joint {joint} is evaluated before its parent")
        placed.add(joint)
    # The joint records' floats (after the parent) are finite.
    for j in range(joints):
        require(all(finite(x) for x in struct.unpack_from("<34f", data,
                                                          parts["joints"] + 140 * j + 4)),
                f"NON_FINITE: PSTR joint {j}")

    # Pose mean, basis, range, regression and basis offset/scale: finite; min <= max; scale >= 0.
    model_floats = (parts["basis_values"] - parts["pose_mean"]) // 4
    require(all(finite(x) for x in struct.unpack_from(f"<{model_floats}f", data,
                                                      parts["pose_mean"])),
            "NON_FINITE: PSTR model float")
    for i in range(pose_dims):
        low, high = struct.unpack_from("<2f", data, parts["pose_range"] + 8 * i)
        require(low <= high, f"CORRUPT: PSTR pose coordinate {i} range min > max")
    for k in range(basis_dims):
        (scale,) = struct.unpack_from("<f", data, parts["basis_params"] + 8 * k + 4)
        require(scale >= 0, f"CORRUPT: PSTR basis column {k} scale < 0")
    # Basis values: u8 or u16, so every one is below 2^bits by its width; nothing more to check.

    # Skin: finite position and normal, every joint index < J (whatever its weight); the writers'
    # weights sum to 65535 or are all 0.
    for v in range(vertices):
        fields = struct.unpack_from("<6f4B4H", data, parts["skin"] + 36 * v)
        require(all(finite(x) for x in fields[:6]), f"NON_FINITE: PSTR vertex {v} skin")
        require(all(j < joints for j in fields[6:10]), f"CORRUPT: PSTR vertex {v} joint index")
        require(sum(fields[10:14]) in (0, 65535), f"WRITER: PSTR vertex {v} weights sum")
    return dict(order=order, vertices=vertices, joints=joints, pose_dims=pose_dims,
                basis_dims=basis_dims, model=model, bits=bits, model_joint=model_joint, kind=kind,
                bounces=bounces, albedo=albedo, flags=flags)


def f32(x):
    """x rounded to the nearest f32."""
    return struct.unpack("<f", struct.pack("<f", x))[0]


# A CLTH thread's floats in record order: (name, low, high, low excluded), SPEC.md §7.4; pi is
# compared as the f32 nearest it.
CLTH_THREAD_FLOATS = (("eta", 1, 4, False), ("albedo", 0, 1, False), ("albedo", 0, 1, False),
                      ("albedo", 0, 1, False), ("k_d", 0, 1, False),
                      ("gamma_s", 0, f32(math.pi), True), ("gamma_v", 0, f32(math.pi), True),
                      ("coverage", 0, 1, False))


def read_clth_fabric(data, at, tangent_count):
    """One CLTH fabric record: name padding, thread floats and ranges, coverages. Returns the name
    and the threads' (first, count)."""
    name = data[at:at + 32]
    length = name.find(b"\0") if b"\0" in name else 32
    require(length > 0, "CORRUPT: CLTH empty name")
    require(name[length:] == bytes(32 - length), "CORRUPT: CLTH name padding")
    threads, coverages = [], []
    for j in range(2):
        t = at + 32 + 64 * j
        floats = struct.unpack_from("<8f", data, t)
        for x, (what, low, high, low_excluded) in zip(floats, CLTH_THREAD_FLOATS):
            require(finite(x), f"NON_FINITE: CLTH {what}")
            require(low <= x <= high and not (low_excluded and x == low), f"CORRUPT: CLTH {what}")
        first, count = struct.unpack_from("<2I", data, t + 32)
        require(1 <= count <= 16, "CORRUPT: CLTH thread tangent count")
        require(first + count <= tangent_count, "CORRUPT: CLTH thread range")
        require(data[t + 40:t + 64] == bytes(24), "CORRUPT: CLTH thread reserved")
        threads.append((first, count))
        coverages.append(floats[7])
    require(coverages[0] + coverages[1] <= 1, "CORRUPT: CLTH coverages")
    return name[:length], threads


def read_clth(data, element_count):
    """CLTH, SPEC.md §7.4: header fields, records, the exact size, names UTF-8 and distinct,
    offsets distinct per thread, then every factorisation's scales, values and padding."""
    require(len(data) >= 64, "CORRUPT: CLTH header")
    fabrics, tangents, tables, xi_size, levels = struct.unpack_from("<5I", data)
    lambda_min, lambda_max = struct.unpack_from("<2f", data, 20)
    view_theta, view_phi, bits, flags = struct.unpack_from("<4I", data, 28)
    require(1 <= fabrics <= 64, "CORRUPT: CLTH fabric count")
    require(1 <= tangents <= 1024, "CORRUPT: CLTH tangent count")
    require(1 <= tables <= 1024, "CORRUPT: CLTH table count")
    require(2 <= xi_size <= 256, "CORRUPT: CLTH N_xi")
    require(1 <= levels <= 64, "CORRUPT: CLTH levels")
    require(finite(lambda_min), "NON_FINITE: CLTH lambda_min")
    require(lambda_min > 0, "CORRUPT: CLTH lambda_min")
    require(finite(lambda_max), "NON_FINITE: CLTH lambda_max")
    require(lambda_max >= lambda_min, "CORRUPT: CLTH lambda_max")
    require(levels != 1 or lambda_max == lambda_min, "CORRUPT: CLTH one level, two sharpnesses")
    require(2 <= view_theta <= 256, "CORRUPT: CLTH N_theta")
    require(2 <= view_phi <= 256, "CORRUPT: CLTH N_phi")
    require(bits in (8, 16), "CORRUPT: CLTH bits")
    require(flags == 0, "CORRUPT: CLTH flags")
    require(data[44:64] == bytes(20), "CORRUPT: CLTH reserved")
    require(fabrics == element_count, "CORRUPT: CLTH fabric count is not the element count")

    tangents_at = 64 + 160 * fabrics
    tables_at = tangents_at + 16 * tangents
    data_at = tables_at + 16 * tables
    require(len(data) >= data_at, "CORRUPT: CLTH records")
    fabric_records = [read_clth_fabric(data, 64 + 160 * f, tangents) for f in range(fabrics)]
    offsets = []
    for g in range(tangents):
        offset, multiplicity, table, mirror = struct.unpack_from("<f3I", data, tangents_at + 16 * g)
        require(finite(offset), "NON_FINITE: CLTH offset")
        require(abs(offset) <= f32(math.pi / 2), "CORRUPT: CLTH offset")
        require(1 <= multiplicity <= 64, "CORRUPT: CLTH multiplicity")
        require(table < tables, "CORRUPT: CLTH table index")
        require(mirror in (0, 1), "CORRUPT: CLTH mirror")
        offsets.append(offset)
    ranks = []
    for q in range(tables):
        rank, cone_rank, reserved0, reserved1 = struct.unpack_from("<4I", data, tables_at + 16 * q)
        require(1 <= rank <= 64 and 1 <= cone_rank <= 64, "CORRUPT: CLTH rank")
        require(reserved0 == 0 and reserved1 == 0, "CORRUPT: CLTH table reserved")
        ranks += [rank, cone_rank]
    rows, columns, value_size = levels * xi_size * xi_size, view_theta * view_phi, bits // 8

    def factor_size(rank):
        return 8 * rank + padded4(columns * rank * value_size) + padded4(rows * rank * value_size)

    require(len(data) == data_at + sum(factor_size(r) for r in ranks), "CORRUPT: CLTH size")

    names = [name for name, _ in fabric_records]
    for name in names:
        try:
            name.decode("utf-8", errors="strict")
        except UnicodeDecodeError:
            raise Invalid("CORRUPT: CLTH name is not UTF-8")
    require(len(set(names)) == len(names), "CORRUPT: CLTH names repeat")
    for _, threads in fabric_records:
        for first, count in threads:
            thread = offsets[first:first + count]
            require(len(set(thread)) == len(thread), "CORRUPT: CLTH offset repeats in a thread")

    at, invalid = data_at, -(1 << (bits - 1))
    for rank in ranks:
        scales = struct.unpack_from(f"<{2 * rank}f", data, at)
        require(all(finite(x) for x in scales), "NON_FINITE: CLTH scale")
        require(all(x >= 0 for x in scales), "CORRUPT: CLTH scale < 0")
        at += 8 * rank
        for count in (columns * rank, rows * rank):  # V, then U
            values = struct.unpack_from(f"<{count}{'b' if bits == 8 else 'h'}", data, at)
            require(invalid not in values, "CORRUPT: CLTH value -128 / -32768")
            end, padded_end = at + count * value_size, at + padded4(count * value_size)
            require(data[end:padded_end] == bytes(padded_end - end), "CORRUPT: CLTH padding")
            at = padded_end
    return dict(fabrics=fabrics, tangents=tangents, tables=tables, xi_size=xi_size, levels=levels,
                lambda_min=lambda_min, lambda_max=lambda_max, view_theta=view_theta,
                view_phi=view_phi, bits=bits)


FLT_MAX = 3.4028234663852886e38


def read_sfld_shells(data, at, grid):
    """One SFLD shell grid, SPEC.md §7.5; returns its point count S 6 F^2."""
    cx, cy, cz, radius, inner, outer, shells, face = struct.unpack_from("<6f2I", data, at)
    for what, x in (("centre", cx), ("centre", cy), ("centre", cz), ("radius", radius),
                    ("inner", inner), ("outer", outer)):
        require(finite(x), f"NON_FINITE: SFLD {grid} {what}")
    require(radius > 0, f"CORRUPT: SFLD {grid} radius")
    require(inner > 0, f"CORRUPT: SFLD {grid} inner")
    require(1 <= shells <= 64, f"CORRUPT: SFLD {grid} shells")
    require(outer == inner if shells == 1 else outer > inner, f"CORRUPT: SFLD {grid} outer")
    require(radius * outer <= FLT_MAX, f"CORRUPT: SFLD {grid} radius x outer")
    require(1 <= face <= 64, f"CORRUPT: SFLD {grid} face size")
    return shells * 6 * face * face


def read_sfld_floats(data, at, count, what, low=-FLT_MAX, high=FLT_MAX):
    for (x,) in struct.iter_unpack("<f", data[at:at + 4 * count]):
        require(finite(x), f"NON_FINITE: SFLD {what}")
        require(low <= x <= high, f"CORRUPT: SFLD {what}")


def read_sfld_block(data, at, rows, count, value_size, what):
    """A quantised block: rows (offset, scale) pairs, values, zero padding to 4. Returns its end."""
    for offset, scale in struct.iter_unpack("<2f", data[at:at + 8 * rows]):
        require(finite(offset) and finite(scale), f"NON_FINITE: SFLD {what} offset or scale")
        require(scale >= 0, f"CORRUPT: SFLD {what} scale")
    end = at + 8 * rows + count * value_size
    require(data[end:padded4(end)] == bytes(padded4(end) - end), f"CORRUPT: SFLD {what} padding")
    return padded4(end)


def read_sfld(data, element_count, vertex_count):
    """SFLD, SPEC.md §7.5: header fields, shells, the exact size, the blocks' floats, padding."""
    require(len(data) >= 128, "CORRUPT: SFLD header")
    order, terms, glossy, v, n, g, bits, flags = struct.unpack_from("<8I", data)
    require(2 <= order <= 6, "CORRUPT: SFLD order")
    require(1 <= terms <= 8, "CORRUPT: SFLD terms")
    require(glossy in (0, 1), "CORRUPT: SFLD glossy")
    require(glossy or terms == 1, "CORRUPT: SFLD diffuse terms")
    require(v >= 1 and v == vertex_count, "CORRUPT: SFLD vertices")
    require(1 <= n <= 64 and n <= v, "CORRUPT: SFLD basis size")
    require(4 <= g <= 64 if glossy else g == 0, "CORRUPT: SFLD BRDF grid")
    require(bits in (8, 16), "CORRUPT: SFLD bits")
    require(flags == 0, "CORRUPT: SFLD flags")
    p_oof = read_sfld_shells(data, 32, "OOF")
    p_srf = read_sfld_shells(data, 64, "SRF")
    require(data[96:128] == bytes(32), "CORRUPT: SFLD reserved")
    require(element_count == 1, "CORRUPT: SFLD element count")
    n2, b = order * order, bits // 8

    def q(rows, count):
        return 8 * rows + padded4(count * b)
    size = (128 + 12 * v + 4 * terms * g * g + q(terms * n2, v * terms * n2) + q(n2, p_oof * n2)
            + q(n, n * v) + 4 * v + 4 * n * n + q(n * terms * n2, n * terms * p_srf * n2))
    require(len(data) == size, "CORRUPT: SFLD size")
    read_sfld_floats(data, 128, 3 * v, "albedo", 0.0, 1.0)
    at = 128 + 12 * v
    read_sfld_floats(data, at, terms * g * g, "g table")
    at += 4 * terms * g * g
    at = read_sfld_block(data, at, terms * n2, v * terms * n2, b, "transfer")
    at = read_sfld_block(data, at, n2, p_oof * n2, b, "OOF")
    at = read_sfld_block(data, at, n, n * v, b, "basis")
    read_sfld_floats(data, at, v, "vertex weights", 0.0)
    at += 4 * v
    read_sfld_floats(data, at, n * n, "inverse normal matrix")
    at += 4 * n * n
    read_sfld_block(data, at, n * terms * n2, n * terms * p_srf * n2, b, "SRF")
    return dict(order=order, terms=terms, glossy=glossy, vertices=v, basis=n, brdf_grid=g,
                bits=bits, oof_points=p_oof, srf_points=p_srf)


def utf8(data):
    try:
        data.decode("utf-8", errors="strict")
        return True
    except UnicodeDecodeError:
        return False


def read_scne(data, element_count):
    """SCNE, SPEC.md §7.6: header fields, exact size, each record, its strings and rest matrix."""
    require(len(data) >= 16, "CORRUPT: SCNE header")
    objects, record_size, string_size, reserved = struct.unpack_from("<4I", data)
    require(objects <= 65536, "CORRUPT: SCNE object count")
    require(record_size >= 96 and record_size % 16 == 0, "CORRUPT: SCNE record size")
    require(reserved == 0, "CORRUPT: SCNE reserved")
    strings = 16 + objects * record_size
    require(len(data) == strings + string_size, "CORRUPT: SCNE size")
    require(element_count == objects, "CORRUPT: SCNE element count")
    table = data[strings:]
    for i in range(objects):
        at = 16 + i * record_size
        (technique, flags, name_offset, name_size, blob_offset, blob_size, node,
         reserved) = struct.unpack_from("<8I", data, at)
        rest = struct.unpack_from("<16f", data, at + 32)
        what = f"SCNE object {i}"
        require(all(0x20 <= (technique >> shift) & 0xFF <= 0x7E for shift in (0, 8, 16, 24)),
                f"CORRUPT: {what} technique tag")
        require(flags == 0, f"CORRUPT: {what} flags")
        require(reserved == 0, f"CORRUPT: {what} reserved")
        require(1 <= name_size <= 255, f"CORRUPT: {what} name size")
        require(name_offset + name_size <= string_size, f"CORRUPT: {what} name range")
        require(1 <= blob_size <= 1024, f"CORRUPT: {what} blob size")
        require(blob_offset + blob_size <= string_size, f"CORRUPT: {what} blob range")
        name = table[name_offset:name_offset + name_size]
        path = table[blob_offset:blob_offset + blob_size]
        require(b"\0" not in name and utf8(name), f"CORRUPT: {what} name")
        require(b"\0" not in path and utf8(path), f"CORRUPT: {what} blob path")
        require(b"\\" not in path and b":" not in path, f"CORRUPT: {what} blob path separator")
        require(not path.startswith(b"/"), f"CORRUPT: {what} blob path is absolute")
        require(all(c not in (b"", b".", b"..") for c in path.split(b"/")),
                f"CORRUPT: {what} blob path component")
        require(all(finite(x) for x in rest), f"NON_FINITE: {what} rest")
        require(rest[3] == 0 and rest[7] == 0 and rest[11] == 0 and rest[15] == 1,
                f"CORRUPT: {what} rest last row")
    return dict(objects=objects, record_size=record_size, string_size=string_size)


def read(blob):
    size = len(blob)
    require(size >= 4, "TRUNCATED: fewer than 4 bytes")
    require(blob[:4] == b"PRTK", "BAD_MAGIC")
    require(size >= 64, "TRUNCATED: shorter than the header")
    (major, minor, header_size, flags, total, table_offset, count,
     checksum) = struct.unpack_from("<HHIIQQII", blob, 4)
    require(major == 1, "UNSUPPORTED_VERSION")
    require(header_size >= 64 and header_size % 16 == 0, "CORRUPT: header_size")
    require(total <= size, "TRUNCATED: total_size")
    require(total >= size, "SIZE_MISMATCH")
    require(header_size <= total, "CORRUPT: header_size > total_size")
    require(flags & 0xFFFF == 0, "UNSUPPORTED_FEATURE: critical header flag")
    require(blob[56:64] == bytes(8), "CORRUPT: reserved header bytes")
    require(count <= 4096, "CORRUPT: section_count")
    require(table_offset == header_size, "CORRUPT: table_offset")
    table_end = table_offset + 48 * count
    require(table_end <= total, "CORRUPT: table past the end")

    sections, end = [], table_end
    for i in range(count):
        (tag, sflags, codec, layout, scheck, reserved, offset, stored, raw,
         elements) = struct.unpack_from("<4sHBBIIQQQQ", blob, table_offset + 48 * i)
        known = (tag, layout) in KINDS
        require(all(0x20 <= c <= 0x7E for c in tag), "CORRUPT: tag")
        require(sflags & ~1 == 0, "UNSUPPORTED_FEATURE: section flags")
        require(reserved == 0, "CORRUPT: section reserved")
        require(codec in (0, 1), "UNSUPPORTED_FEATURE: codec")
        require(known or not sflags & 1, "UNSUPPORTED_FEATURE: unknown required section")
        require(offset == align16(end), "CORRUPT: offset not canonical")
        require(offset + stored <= total, "CORRUPT: section past the end")
        require(codec != 0 or stored == raw, "CORRUPT: stored != raw")
        require(codec != 1 or (stored >= 9 and raw <= 32768 * stored), "CORRUPT: zstd sizes")
        if known and KINDS[(tag, layout)] is not None:
            require(elements * KINDS[(tag, layout)] == raw, "CORRUPT: element_count")
        else:
            require(elements <= raw, "CORRUPT: element_count")
        require(all(s["tag"] != tag for s in sections), "CORRUPT: duplicate tag")
        sections.append(dict(tag=tag, flags=sflags, codec=codec, layout=layout, checksum=scheck,
                             offset=offset, stored=stored, raw=raw, elements=elements,
                             known=known))
        end = offset + stored
    require(total == align16(end), "CORRUPT: total_size is not the padded end")
    by_tag = {s["tag"]: s for s in sections if s["known"]}
    for needy in (b"TRIS", b"SFLD") + PER_VERTEX:
        require(needy not in by_tag or b"VPOS" in by_tag, "CORRUPT: needs VPOS")
    require(b"SFLD" not in by_tag or b"VNRM" in by_tag, "CORRUPT: SFLD needs VNRM")
    for per_vertex in PER_VERTEX:
        if per_vertex in by_tag:
            require(by_tag[per_vertex]["elements"] == by_tag[b"VPOS"]["elements"],
                    "CORRUPT: element count is not the vertex count")

    header = bytearray(blob[:header_size])
    header[36:40] = bytes(4)
    require(crc32c(bytes(header) + blob[table_offset:table_end]) == checksum,
            "CHECKSUM_MISMATCH: header")
    end = table_end
    for s in sections:
        require(blob[end:s["offset"]] == bytes(s["offset"] - end), "CORRUPT: padding")
        data = blob[s["offset"]:s["offset"] + s["stored"]]
        require(crc32c(data) == s["checksum"], "CHECKSUM_MISMATCH: section")
        end = s["offset"] + s["stored"]
        if not s["known"] or s["codec"] != 0:
            continue
        if s["tag"] == b"INFO":
            try:
                data.decode("utf-8", errors="strict")
            except UnicodeDecodeError:
                raise Invalid("CORRUPT: INFO is not UTF-8")
        elif s["tag"] in (b"VPOS", b"VNRM", b"VTAN"):
            for (bits,) in struct.iter_unpack("<I", data):
                require(bits & 0x7F800000 != 0x7F800000, "NON_FINITE")
        elif s["tag"] == b"TRIS":
            vertices = by_tag[b"VPOS"]["elements"]
            for (index,) in struct.iter_unpack("<I", data):
                require(index < vertices, "INDEX_OUT_OF_RANGE")
        elif s["tag"] == b"SHTR":
            s["header"] = read_shtr(data, s["elements"])
        elif s["tag"] == b"WVLT":
            s["header"] = read_wvlt(data, s["elements"])
        elif s["tag"] == b"PSTR":
            s["header"] = read_pstr(data, s["elements"])
        elif s["tag"] == b"CLTH":
            s["header"] = read_clth(data, s["elements"])
        elif s["tag"] == b"SFLD":
            s["header"] = read_sfld(data, s["elements"], by_tag[b"VPOS"]["elements"])
        elif s["tag"] == b"SCNE":
            s["header"] = read_scne(data, s["elements"])
    require(blob[end:total] == bytes(total - end), "CORRUPT: final padding")
    return (major, minor), sections


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    blob = open(sys.argv[1], "rb").read()
    try:
        version, sections = read(blob)
    except Invalid as failure:
        print(f"{sys.argv[1]}: invalid: {failure}")
        return 1
    print(f"{sys.argv[1]}: valid prtkit blob {version[0]}.{version[1]}, {len(blob)} bytes")
    for s in sections:
        codec = "zstd" if s["codec"] else "none"
        print(f"  {s['tag'].decode()} v{s['layout']} flags={s['flags']} {codec} "
              f"offset={s['offset']} stored={s['stored']} raw={s['raw']} "
              f"elements={s['elements']}")
        if "header" in s:
            print("    " + " ".join(f"{k}={v}" for k, v in s["header"].items()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
