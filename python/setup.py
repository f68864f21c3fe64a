"""Builds the meshd package, generating the meshd.v1 stubs from the repository's proto/ first.

The stubs are never committed: build_py runs protoc with the gRPC Python plugin into the build
directory (meshd/v1/*_pb2.py, *_pb2_grpc.py), so that they always match the proto files they are
built from. Where things are found:

  MESHD_PROTO_DIR            folder holding meshd/v1/*.proto (default: ../proto next to this file)
  MESHD_PROTOC               protoc (default: protoc on PATH; Debian: protobuf-compiler)
  MESHD_GRPC_PYTHON_PLUGIN   grpc_python_plugin (default: on PATH; Debian: protobuf-compiler-grpc)

Without protoc and the plugin, grpcio-tools' bundled protoc (python3 -m grpc_tools.protoc) is
used when it is importable.
"""

import glob
import importlib.util
import os
import re
import shutil
import subprocess
import sys

from setuptools import setup
from setuptools.command.build_py import build_py

HERE = os.path.dirname(os.path.abspath(__file__))
SERVICE = re.compile(r"^service\s", re.MULTILINE)


def proto_dir():
    path = os.environ.get("MESHD_PROTO_DIR") or os.path.join(HERE, os.pardir, "proto")
    path = os.path.abspath(path)
    if not glob.glob(os.path.join(path, "meshd", "v1", "*.proto")):
        sys.exit(f"meshd: no meshd/v1/*.proto under {path}; build from a clone of the repository "
                 "or set MESHD_PROTO_DIR to its proto/ folder")
    return path


def protoc_command():
    """The protoc command line up to its output options, or exits saying what is missing."""
    protoc = os.environ.get("MESHD_PROTOC") or shutil.which("protoc")
    plugin = os.environ.get("MESHD_GRPC_PYTHON_PLUGIN") or shutil.which("grpc_python_plugin")
    if protoc and plugin:
        return [protoc, f"--plugin=protoc-gen-grpc_python={plugin}"]
    if importlib.util.find_spec("grpc_tools") is not None:
        return [sys.executable, "-m", "grpc_tools.protoc"]
    sys.exit("meshd: generating the gRPC stubs needs protoc and grpc_python_plugin (Debian: "
             "protobuf-compiler protobuf-compiler-grpc) or grpcio-tools")


def generate_stubs(out_root):
    """Writes meshd/v1/*_pb2.py and *_pb2_grpc.py (and an __init__.py) under out_root."""
    source = proto_dir()
    protos = sorted(os.path.relpath(p, source)
                    for p in glob.glob(os.path.join(source, "meshd", "v1", "*.proto")))
    # Only the files that define a service get gRPC stubs (the plugin writes an empty module
    # for the others).
    services = [p for p in protos if SERVICE.search(open(os.path.join(source, p)).read())]
    os.makedirs(os.path.join(out_root, "meshd", "v1"), exist_ok=True)
    protoc = protoc_command() + [f"--proto_path={source}"]
    subprocess.run(protoc + [f"--python_out={out_root}", *protos], check=True)
    subprocess.run(protoc + [f"--grpc_python_out={out_root}", *services], check=True)
    with open(os.path.join(out_root, "meshd", "v1", "__init__.py"), "w") as f:
        f.write('"""meshd.v1 messages and gRPC stubs, generated from proto/ at build time."""\n')


class BuildWithStubs(build_py):
    def run(self):
        # An editable install imports meshd from this folder, so its stubs go here (ignored by
        # git); a normal build puts them beside the copied sources.
        generate_stubs(HERE if getattr(self, "editable_mode", False) else self.build_lib)
        super().run()


setup(cmdclass={"build_py": BuildWithStubs})
