#!/usr/bin/env bash
# Checks docker/ where Docker itself is not at hand: the Dockerfile's build stage runs
# scripts/build.sh (so that the image and CI cannot drift) and its runtime stage is the one
# README describes; compose.yaml and k8s/deployment.yaml parse and keep their GPU, probes and
# grace period.
#
#   check_docker_files.sh SOURCE_DIR [PYTHON]
#
# Exit status: 0 when all pass, 1 on a failure, 77 (ctest's skip) when PYTHON lacks yaml (the
# Dockerfile checks have run by then).
set -euo pipefail
src=${1:?usage: check_docker_files.sh SOURCE_DIR [PYTHON]}
python=${2:-python3}
dockerfile=$src/docker/Dockerfile
failures=0
check() {  # check DESCRIPTION COMMAND...
  local what=$1
  shift
  if "$@"; then echo "PASS $what"; else echo "FAIL $what"; failures=$((failures + 1)); fi
}

# Instructions of the Dockerfile with continuation lines joined and comments dropped.
instructions=$(sed -e 's/^[[:space:]]*#.*$//' "$dockerfile" | sed -e ':a' -e '/\\$/N; s/\\\n//; ta')
# The stage named build: from its FROM to the next FROM.
build_stage=$(awk '/^FROM .* AS build$/ { on = 1; next } /^FROM / { on = 0 } on' <<<"$instructions")
runtime_stage=$(awk '/^FROM / { stage = $0 } stage !~ / AS build$/' <<<"$instructions")

check "the build stage is FROM nvidia/cuda:*-devel-ubuntu24.04" \
  grep -Eq '^FROM nvidia/cuda:[^ ]+-devel-ubuntu24\.04 AS build$' <<<"$instructions"
check "the build stage runs scripts/build.sh, as CI does" \
  grep -Eq '^RUN .*(^|[ ;&|])scripts/build\.sh( |$)' <<<"$build_stage"
check "the runtime stage is FROM nvidia/cuda:*-runtime-ubuntu24.04" \
  grep -Eq '^FROM nvidia/cuda:[^ ]+-runtime-ubuntu24\.04$' <<<"$runtime_stage"
check "the runtime stage copies meshd and meshctl from the build stage" \
  grep -Eq '^COPY --from=build .*/meshd .*/meshctl ' <<<"$runtime_stage"
non_root() {  # the last USER of the runtime stage names neither root nor uid 0
  local user
  user=$(grep -E '^USER ' <<<"$runtime_stage" | tail -1 | cut -d' ' -f2 | cut -d: -f1)
  [ -n "$user" ] && [ "$user" != root ] && [ "$user" != 0 ]
}
check "the runtime stage runs as a non-root user" non_root
check "EXPOSE 50051 9464" grep -Eq '^EXPOSE 50051 9464$' <<<"$runtime_stage"
check "ENTRYPOINT meshd on 0.0.0.0:50051 with metrics on 0.0.0.0:9464" \
  grep -Fxq 'ENTRYPOINT ["meshd", "--listen", "0.0.0.0:50051", "--metrics", "0.0.0.0:9464"]' \
  <<<"$runtime_stage"
check "HEALTHCHECK calls meshctl health on 127.0.0.1:50051 with a deadline" \
  grep -Eq '^HEALTHCHECK .*CMD \["meshctl", "health", "--server", "127.0.0.1:50051", '\
'"--deadline", "[0-9.]+"\]' <<<"$runtime_stage"

if ! "$python" -c 'import yaml' 2>/dev/null; then
  echo "SKIP the YAML checks: $python cannot import yaml (python3-yaml)"
  [ "$failures" -eq 0 ] && exit 77 || exit 1
fi
"$python" - "$src/docker" <<'EOF' || failures=$((failures + 1))
import sys
import yaml

docker = sys.argv[1]
failures = 0


def check(what, ok):
    global failures
    print(("PASS " if ok else "FAIL ") + what)
    failures += not ok


docs = list(yaml.safe_load_all(open(f"{docker}/k8s/deployment.yaml")))
kinds = {d["kind"]: d for d in docs if d}
check("k8s/deployment.yaml parses into a Deployment and a Service",
      {"Deployment", "Service"} <= kinds.keys())
pod = kinds["Deployment"]["spec"]["template"]
meshd = next(c for c in pod["spec"]["containers"] if c["name"] == "meshd")
for probe in ("livenessProbe", "readinessProbe"):
    check(f"{probe} is a native gRPC probe on port 50051",
          meshd.get(probe, {}).get("grpc", {}).get("port") == 50051)
check("the container's limits ask for nvidia.com/gpu: 1",
      meshd["resources"]["limits"].get("nvidia.com/gpu") == 1)
args = meshd.get("args", [])
drain = float(args[args.index("--drain-timeout") + 1]) if "--drain-timeout" in args else 30.0
grace = pod["spec"].get("terminationGracePeriodSeconds", 30)
check(f"terminationGracePeriodSeconds ({grace}) is above --drain-timeout ({drain:g})",
      grace > drain)
annotations = pod["metadata"].get("annotations", {})
check("the pods carry Prometheus scrape annotations for port 9464",
      annotations.get("prometheus.io/scrape") == "true"
      and annotations.get("prometheus.io/port") == "9464")
service = kinds["Service"]["spec"]
check("the Service selects the Deployment's pods and serves 50051",
      service["selector"].items() <= pod["metadata"]["labels"].items()
      and any(p["port"] == 50051 for p in service["ports"]))

compose = yaml.safe_load(open(f"{docker}/compose.yaml"))["services"]["meshd"]
devices = compose["deploy"]["resources"]["reservations"]["devices"]
check("compose.yaml reserves an NVIDIA GPU",
      any(d.get("driver") == "nvidia" and "gpu" in d.get("capabilities", []) for d in devices))
check("compose.yaml builds docker/Dockerfile",
      compose["build"]["dockerfile"] == "docker/Dockerfile")
sys.exit(1 if failures else 0)
EOF

if [ "$failures" -ne 0 ]; then
  echo "check_docker_files: some checks failed"
  exit 1
fi
echo "check_docker_files: all checks passed"
