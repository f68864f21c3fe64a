#!/usr/bin/env python3
"""A small meshd client: mesh a request file on a meshd server and write the mesh with meshio.

    meshd_client.py [--server HOST:PORT] [--deadline S] [--stubs DIR] REQUEST.textproto OUT

Reads a text-format meshd.v1.MeshRequest (examples/*.textproto), calls MeshService.Generate
with a deadline, prints progress to stderr, joins the result chunks, checks their SHA-256
against the `done` event, and writes the triangles (a volume request's tetrahedra) with meshio;
the format follows OUT's extension (.vtu, .msh, .xdmf, ...). On an error it prints the server's
status and message (which names the field of a bad request) and exits 1.

Needs grpcio, protobuf and meshio (Debian: python3-grpcio python3-protobuf python3-meshio; pip:
grpcio protobuf meshio) and the Python stubs of proto/meshd/v1, from either
  - the build: target meshd_python_stubs writes them to <build>/python; pass --stubs build/python
  - protoc, from the repository root, into a folder of your own:
      pip install grpcio-tools
      python3 -m grpc_tools.protoc -I proto --python_out=stubs --grpc_python_out=stubs \
          proto/meshd/v1/*.proto
    or, with Debian's protobuf-compiler-grpc instead of grpcio-tools:
      protoc -I proto --python_out=stubs --grpc_python_out=stubs \
          --plugin=protoc-gen-grpc_python="$(command -v grpc_python_plugin)" proto/meshd/v1/*.proto
    then pass --stubs stubs.

Example (meshd listening on its default 127.0.0.1:50051):
    python3 examples/python/meshd_client.py --stubs build/python examples/g1_disk.textproto g1.vtu
"""

import argparse
import hashlib
import sys
import time


def parse_args():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("request", help="text-format meshd.v1.MeshRequest")
    parser.add_argument("output", help="mesh file to write; meshio picks the format")
    parser.add_argument("--server", default="127.0.0.1:50051", help="meshd's HOST:PORT")
    parser.add_argument("--deadline", type=float, default=600,
                        help="seconds the whole call may take (default 600)")
    parser.add_argument("--stubs", help="folder holding meshd/v1/*_pb2.py (default: sys.path)")
    return parser.parse_args()


def generate(stub, request, deadline):
    """Runs Generate and returns (payload, done): the joined result chunks and the done event.
    Raises grpc.RpcError when the server ends the call with an error."""
    chunks, done, last_line = [], None, 0.0
    # The deadline bounds the whole stream; when it passes, the server cancels the job.
    for event in stub.Generate(request, timeout=deadline):
        kind = event.WhichOneof("event")
        if kind == "queued":
            print(f"job {event.job_id} queued (position {event.queued.position})", file=sys.stderr)
        elif kind == "started":
            print(f"started on {event.started.device}", file=sys.stderr)
        elif kind == "progress" and time.monotonic() - last_line >= 0.5:
            # Progress comes up to 100 times a second; a line every half second is plenty.
            last_line = time.monotonic()
            p = event.progress
            print(f"  iteration {p.iteration}  max move {p.max_move:.1e} h0  {p.nodes} nodes  "
                  f"{p.elapsed_s:.2f} s", file=sys.stderr)
        elif kind == "result_chunk":
            c = event.result_chunk
            # Chunks arrive in order; check it rather than trust it.
            if c.index != len(chunks):
                raise ValueError(f"result chunk {c.index} arrived as number {len(chunks)}")
            chunks.append(c.data)
        elif kind == "done":
            done = event.done
    if done is None:
        raise ValueError("the stream ended without a done event")
    return b"".join(chunks), done


def main():
    args = parse_args()
    if args.stubs:
        sys.path.insert(0, args.stubs)
    try:
        import grpc
        import meshio
        import numpy as np
        from google.protobuf import text_format
        from meshd.v1 import mesh_pb2, request_pb2, service_pb2_grpc
    except ImportError as e:
        sys.exit(f"meshd_client: {e} (see this file's docstring for what to install)")

    with open(args.request) as f:
        request = text_format.Parse(f.read(), request_pb2.MeshRequest())

    with grpc.insecure_channel(args.server) as channel:
        stub = service_pb2_grpc.MeshServiceStub(channel)
        try:
            payload, done = generate(stub, request, args.deadline)
        except grpc.RpcError as e:
            # e.g. INVALID_ARGUMENT: h0: must be finite and > 0 (got -1)
            print(f"meshd_client: {e.code().name}: {e.details()}", file=sys.stderr)
            return 1
        except ValueError as e:
            print(f"meshd_client: {e}", file=sys.stderr)
            return 1

    digest = hashlib.sha256(payload).hexdigest()
    if len(payload) != done.result_bytes or digest != done.result_sha256:
        print(f"meshd_client: the result's SHA-256 {digest} differs from the server's "
              f"{done.result_sha256}", file=sys.stderr)
        return 1
    mesh = mesh_pb2.MeshData.FromString(payload)

    q = done.quality
    if mesh.dimension == 3:
        # A volume (request field `volume`): points #N by 3, tetrahedra #M by 4.
        points = np.asarray(mesh.points).reshape(-1, 3)
        cells = np.asarray(mesh.tetrahedra, dtype=np.int64).reshape(-1, 4)
        meshio.Mesh(points, [("tetra", cells)]).write(args.output)
        print(f"nodes {done.nodes} tetrahedra {done.tetrahedra} iterations "
              f"{done.stats.iterations} q_min {q.q_min:.3f} min dihedral "
              f"{q.min_dihedral_deg:.1f} deg on {done.device}")
    else:
        # MeshData is flat: points #N by 2, triangles #M by 3. meshio wants 3D points for most
        # formats (VTU among them), so z = 0.
        points = np.zeros((len(mesh.points) // 2, 3))
        points[:, :2] = np.asarray(mesh.points).reshape(-1, 2)
        cells = np.asarray(mesh.triangles, dtype=np.int64).reshape(-1, 3)
        meshio.Mesh(points, [("triangle", cells)]).write(args.output)
        print(f"nodes {done.nodes} triangles {done.triangles} iterations "
              f"{done.stats.iterations} q_min {q.q_min:.3f} q_mean {q.q_mean:.4f} on "
              f"{done.device}")
    print(f"wrote {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
