#!/usr/bin/env bash
# Runs on the GPU machine from a bundle of the executables (.gpu/, made by the gpu-bundle tool):
# the GPU tests, compute-sanitizer (memcheck, racecheck) on the agreement tests, a per-phase
# profile, the GPU benchmark, and the service on a GPU (its tests, meshd + meshctl end to end,
# the overhead), the device's Delaunay builder against CGAL (delaunay), many small jobs through
# meshd (throughput), and one GPU against all of a host's (gpus), and the 3D engine's steps on
# the GPU against the host's cores (volumes). Logs go to $OUT (or ./gpu-logs).
# Usage: scripts/gpu_check.sh [tests|sanitize|profile|bench|delaunay|primitives|primitives_cpu|service|throughput|gpus|volumes]...
set -uo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
run=$here/.gpu/run.sh
out=${OUT:-$here/gpu-logs}
mkdir -p "$out"
steps=("$@")
[ ${#steps[@]} -gt 0 ] || steps=(tests sanitize bench)
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader | tee "$out/device.txt"
for step in "${steps[@]}"; do
  case $step in
    tests)
      $run kernels_gpu_engine_test 2>&1 | tee "$out/gpu_tests.log" | tail -25 ;;
    sanitize)
      san=$(command -v compute-sanitizer || echo /usr/local/cuda/bin/compute-sanitizer)
      # MESHD_SANITIZE_FILTER narrows both tools to some tests (e.g. a new kernel's).
      filter=${MESHD_SANITIZE_FILTER:-'Geometries/GpuAgreement.OneStep*:Geometries/GpuAgreement.Density*:Geometries/GpuAgreement.Initial*:GpuEngine.*:*Repair*/1'}
      # memcheck with the kernels launched one by one and with the step graph and the flip
      # rounds' cooperative loop, also over whole meshes of G1 and G5 (node removal,
      # completion). While the flip rounds ran in a graph with a conditional node, memcheck
      # faulted there now and then without naming an access (bench/RESULTS.md, 2026-11-26).
      # racecheck crashes on graphs with conditional nodes, so it runs the kernels launched one
      # by one; over a whole mesh it takes ten minutes.
      whole='*StepGraph*:*StepsTogether*:*WholeMesh*/0:*WholeMesh*/4'
      [ -n "${MESHD_SANITIZE_FILTER:-}" ] && whole=''
      runs=("memcheck 0 $filter${whole:+:$whole}"
            "memcheck 1 $filter${whole:+:$whole}"
            "racecheck 0 $filter")
      for run_args in "${runs[@]}"; do
        read -r tool graph tests <<< "$run_args"
        log="$out/sanitizer_${tool}_graph$graph.log"
        MESHD_GPU_STEP_GRAPH=$graph LD_LIBRARY_PATH=$here/.gpu/lib "$san" --tool $tool \
          --error-exitcode 1 "$here/.gpu/bin/kernels_gpu_engine_test" --gtest_filter="$tests" \
          > "$log" 2>&1
        echo "compute-sanitizer $tool, step graph $graph: exit $? ($(grep -cE '(ERROR|RACECHECK) SUMMARY: 0' "$log") clean summaries)"
        tail -3 "$log"
      done ;;
    delaunay)
      # The device's Delaunay builder against CGAL on this host, at the issue's sizes.
      $run delaunay_bench --repeat 3 100000 1000000 4000000 2>&1 | tee "$out/delaunay.log" ;;
    profile)
      # Seconds per phase of the GPU engine at the issue's two sizes (best of 3).
      req="examples/g1_disk.textproto examples/g2_square_hole.textproto"
      for n in 20000 1000000; do
        $run meshbench --backend gpu --repeat 3 --phases --nodes $n $req 2>&1 | tee -a "$out/profile.log"
      done ;;
    bench)
      # G1 and G2 uniform at the issue's sizes, GPU and CPU (all cores) on the same host; beside
      # them what users send: G5 (graded) and the realistic examples.
      req="examples/g1_disk.textproto examples/g2_square_hole.textproto"
      users="examples/g5_graded_hole.textproto examples/plate_with_holes.textproto
             examples/airfoil_channel.textproto examples/l_shape_refined.textproto
             examples/gear.textproto"
      for n in 20000 100000 1000000 4000000; do
        repeat=3; [ $n -gt 1000000 ] && repeat=1
        $run meshbench --backend gpu --repeat $repeat --nodes $n $req 2>&1 | tee -a "$out/bench_gpu.log"
      done
      for n in 10000 100000 1000000; do
        repeat=3; [ $n -ge 1000000 ] && repeat=1
        $run meshbench --backend gpu --repeat $repeat --phases --nodes $n $users 2>&1 |
          tee -a "$out/bench_gpu_users.log"
      done
      for n in 10000 100000; do
        $run meshbench --backend cpu --nodes $n $users 2>&1 | tee -a "$out/bench_cpu_users.log"
      done
      # The step's kernels launched one by one, one step per host round trip, against the graph.
      for n in 20000 1000000; do
        $run meshbench --backend gpu --no-step-graph --repeat 3 --nodes $n $req 2>&1 |
          tee -a "$out/bench_no_graph.log"
      done
      # The step that measures the bars first, as the CPU engine does (the default takes the L0
      # scale from the step before).
      $run meshbench --backend gpu --exact-scale --repeat 3 --nodes 1000000 $req 2>&1 |
        tee -a "$out/bench_exact.log"
      # Per-node force sums: the CSR gather (default) against float atomics.
      for n in 1000000 4000000; do
        $run meshbench --backend gpu --force-sum atomic --nodes $n $req 2>&1 | tee -a "$out/bench_atomic.log"
      done
      for n in 20000 100000 1000000; do
        $run meshbench --backend cpu --nodes $n $req 2>&1 | tee -a "$out/bench_cpu.log"
      done ;;
    volumes)
      # The 3D loop with its steps on the GPU, then on the host's cores, at about 10k, 100k and
      # 175k nodes (a million tetrahedra); triangulations and the finish on all the host's cores.
      cores=$(nproc)
      v="ball box_minus_sphere torus cylinder_graded"
      for n in 10000 100000 175000; do
        $run meshbench3d --backend gpu --threads "$cores" --nodes $n $v 2>&1 | tee -a "$out/bench3d_gpu.log"
        $run meshbench3d --backend cpu --threads "$cores" --nodes $n $v 2>&1 | tee -a "$out/bench3d_cpu.log"
      done ;;
    primitives)
      # Trees of many shapes and long polygons (bench/many_primitives.py) at equal node counts,
      # on the GPU (primitives_cpu: the same on the CPU cores): what the spatial indexes keep.
      dir=$(mktemp -d)
      python3 "$here/bench/many_primitives.py" "$dir"
      reqs="$dir/holes_10.textproto $dir/holes_100.textproto $dir/holes_1000.textproto
            $dir/holes_10000.textproto $dir/ragged_1000.textproto $dir/ragged_100000.textproto
            $dir/ragged_1000000.textproto"
      for n in 200000 1000000; do
        $run meshbench --backend gpu --nodes $n $reqs 2>&1 | tee -a "$out/bench_primitives_gpu.log"
      done
      rm -rf "$dir" ;;
    primitives_cpu)
      # The same on the host's CPU cores (minutes: the long polygons at 200k nodes).
      dir=$(mktemp -d)
      python3 "$here/bench/many_primitives.py" "$dir"
      $run meshbench --backend cpu --nodes 200000 "$dir"/holes_*.textproto "$dir"/ragged_*.textproto \
        2>&1 | tee -a "$out/bench_primitives_cpu.log"
      rm -rf "$dir" ;;
    service)
      $run server_gpu_service_test 2>&1 | tee "$out/gpu_service_tests.log" | tail -6
      # meshd on its defaults (a GPU worker, a CPU worker) and meshctl through it.
      $run meshd > "$out/meshd.log" 2>&1 &
      meshd_pid=$!
      for _ in $(seq 100); do $run meshctl health --deadline 1 > /dev/null 2>&1 && break; sleep 0.2; done
      # Volumes too: on a GPU node they go to the CPU worker.
      for request in examples/*.textproto examples/volumes/*.textproto; do
        $run meshctl generate "$request" -o "$out/$(basename "$request" .textproto).msh" 2>&1 |
          tee -a "$out/meshctl.log" | grep -E "done on|q_min"
      done
      kill -TERM $meshd_pid; wait $meshd_pid; echo "meshd exit $?"
      $run service_overhead --backend gpu --repeat 5 2>&1 | tee "$out/service_overhead_gpu.log"
      $run service_overhead --backend cpu --repeat 3 2>&1 | tee "$out/service_overhead_cpu.log" ;;
    throughput)
      # ~2k-node disks through an in-process meshd: a lone client (latency, each job in
      # lone_jobs.csv), then 64 clients on the GPU with 1 to 24 workers, on the host's CPU cores
      # alone, and on both (auto); then a mix of 500 to 50k nodes.
      cores=$(nproc)
      t() { $run throughput "$@" 2>&1 | tee -a "$out/throughput.log" | tail -n +3; }
      echo "| jobs | nodes | load | ok | jobs/s | p50 ms | p90 ms | p99 ms | max ms | mesh ms (mean) | mesh ms (p99) | on GPU | on CPU | meshd |"
      t --jobs 300 --clients 1 --latencies "$out/lone_jobs.csv" -- --backend gpu |
        sed 's/$/ gpu, 1 worker |/'
      for w in 1 2 4 8 16 24; do
        t --jobs 2000 --clients 64 -- --backend gpu --gpu-workers $w | sed "s/\$/ gpu, $w workers |/"
      done
      t --jobs 2000 --clients 64 -- --backend cpu --cpu-workers "$cores" --cpu-threads 1 |
        sed "s/\$/ cpu, $cores workers of 1 thread |/"
      for w in 4 8; do
        t --jobs 2000 --clients 64 -- --gpu-workers $w --cpu-workers "$cores" --cpu-threads 1 |
          sed "s/\$/ auto, $w GPU + $cores CPU workers |/"
      done
      t --jobs 1000 --clients 64 --nodes 500,2000,10000,50000 -- --gpu-workers 8 \
        --cpu-workers "$cores" --cpu-threads 1 | sed "s/\$/ auto, 8 GPU + $cores CPU workers |/" ;;
    gpus)
      # The same jobs on the first GPU, then on every visible one (8 GPU workers each, every job
      # asking for a GPU), twice in turn: ~2k-node disks and 50k-node ones.
      all=$(nvidia-smi --query-gpu=index --format=csv,noheader | paste -sd, -)
      echo "| GPUs | jobs | nodes | load | ok | jobs/s | p50 ms | p90 ms | p99 ms | max ms | mesh ms (mean) | mesh ms (p99) | on GPU | on CPU |"
      for nodes in 2000 50000; do
        jobs=3000; [ $nodes -gt 10000 ] && jobs=600
        for visible in 0 "$all" 0 "$all"; do
          CUDA_VISIBLE_DEVICES=$visible $run throughput --jobs $jobs --clients 128 --job-backend gpu \
            --nodes $nodes -- --backend gpu --gpu-workers 8 2>&1 | tee -a "$out/gpus.log" |
            tail -n 1 | sed "s/^/| $visible /"
        done
      done ;;
  esac
done
