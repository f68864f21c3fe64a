# Sourced by run.sh and tests/bench/coastline_test.sh: a meshd of their own on a free port.
#
#   start_local_meshd MESHD MESHCTL LOG [meshd flags...]
#
# starts MESHD listening on 127.0.0.1 (port 0: a free one), its output in LOG, and waits up to a
# minute (a busy machine) until it answers health through MESHCTL. Sets meshd_pid, and port once
# it serves; returns 1 with port empty when it does not.
start_local_meshd() {
  local meshd=$1 meshctl=$2 log=$3
  shift 3
  # The log exists before meshd starts: the background job opens it only when it runs, and a
  # read before that failed the caller's `set -e` on a loaded machine.
  : >"$log"
  "$meshd" --listen 127.0.0.1:0 "$@" >"$log" 2>&1 &
  meshd_pid=$!
  port=
  for _ in $(seq 300); do
    port=$(sed -n 's/.*meshd listening on .*(port \([0-9]*\)).*/\1/p' "$log")
    [[ -n $port ]] && "$meshctl" --server "127.0.0.1:$port" health >/dev/null 2>&1 && return 0
    sleep 0.2
  done
  port=
  return 1
}
