"""The audit of a load run: each call that load_generator.py made against what meshd holds.

audit() waits for meshd_live_jobs, meshd_active_streams and meshd_queue_depth to return to 0,
then matches every job of the run in ListJobs to its call by JobOptions.label and checks that
its final state agrees with what the client saw (consistent()), that no call left a job it
should not have, that every job id the client saw is still known, and that meshd_jobs_total
moved by exactly the jobs found. A record is a dict: kind, label, job_id ("" when the client
never saw one), outcome (done, cancelled, deadline, cancel_rpc, rejected, error, bad_result),
and code, sha, stopped_at, cancel_reply where they apply.
"""

import time

import meshd_launcher as ml

RPC_TIMEOUT = 120
SETTLE_TIMEOUT = 10  # s for the gauges to return to 0 once the clients have stopped
# A client cancel or deadline may lose the race against a job that was finishing anyway: the
# server may then call it SUCCEEDED, but only if it finished before the client gave up (plus
# the time a cancel takes to reach a worker between two iterations, and the result's encoding,
# both slower on a busy 2-core machine).
RACE_TOLERANCE_S = 2.0


def consistent(rec, job):
    """Whether the server's final JobInfo agrees with what the client saw; None when it does,
    else why not."""
    S = ml.service_pb2
    state = S.JobState.Name(job.state)
    finished = job.submitted_at + job.queue_wait_s + job.run_s
    outcome = rec["outcome"]
    if outcome == "done":
        ok = job.state == S.JOB_STATE_SUCCEEDED and job.done.result_sha256 == rec["sha"]
    elif outcome in ("cancelled", "deadline"):
        if job.state == S.JOB_STATE_SUCCEEDED:
            rec["race_s"] = finished - rec["stopped_at"]  # > 0: finished after we gave up
        ok = job.state == S.JOB_STATE_CANCELLED or (job.state == S.JOB_STATE_SUCCEEDED and
                                                    rec["race_s"] <= RACE_TOLERANCE_S)
    elif outcome == "cancel_rpc":
        final = rec["cancel_reply"] in (S.JOB_STATE_SUCCEEDED, S.JOB_STATE_CANCELLED)
        ok = job.state in (S.JOB_STATE_SUCCEEDED, S.JOB_STATE_CANCELLED) and (
            not final or job.state == rec["cancel_reply"])
    else:  # rejected calls never leave a job behind
        ok = False
    return None if ok else f"client saw {outcome}, server says {state}"


def audit(metrics_port, stub, records, before, tag, expected):
    """Cross-checks the records with ListJobs and /metrics, `before` being /metrics at the
    start and `expected` the outcomes each kind of call may have: (problems, accounting table
    of client outcome -> {server state or "no job": calls})."""
    problems, S = [], ml.service_pb2

    def gauges_zero():
        m = ml.read_metrics(metrics_port)
        return all(m[g] == 0 for g in ("meshd_live_jobs", "meshd_active_streams",
                                        "meshd_queue_depth")) and m
    t = time.monotonic()
    try:
        after = ml.wait_for("meshd_live_jobs, meshd_active_streams and meshd_queue_depth = 0",
                            gauges_zero, SETTLE_TIMEOUT, 0.1)
        print(f"gauges back to 0 {time.monotonic() - t:.2f} s after the last client stopped")
    except AssertionError as e:
        after = ml.read_metrics(metrics_port)
        problems.append(f"{e}: live {after['meshd_live_jobs']:.0f}, streams "
                        f"{after['meshd_active_streams']:.0f}, "
                        f"queue {after['meshd_queue_depth']:.0f}")

    jobs = stub.ListJobs(S.ListJobsRequest(), timeout=RPC_TIMEOUT).jobs
    server = {j.label: j for j in jobs if j.label.startswith(tag + "-")}
    by_label = {rec["label"]: rec for rec in records}
    for label in server.keys() - by_label.keys():
        problems.append(f"server job {server[label].job_id} ({label}) matches no client call")
    states, table = {}, {}
    for rec in records:
        job = server.get(rec["label"])
        if job is not None:
            states[job.state] = states.get(job.state, 0) + 1
        key = rec["outcome"] + (f" {rec['code']}" if rec["outcome"] in ("rejected", "error")
                                else "")
        column = S.JobState.Name(job.state)[len("JOB_STATE_"):] if job else "no job"
        table.setdefault(key, {})[column] = table.setdefault(key, {}).get(column, 0) + 1
        wrong_code = rec["outcome"] == "rejected" and rec["code"] != (
            "INVALID_ARGUMENT" if rec["kind"] == "invalid" else "UNAVAILABLE")
        if rec["outcome"] not in expected[rec["kind"]] or wrong_code:
            problems.append(f"{rec['label']} ({rec['kind']}): unexpected {rec['outcome']} "
                            f"{rec.get('code', '')}")
        elif job is None and rec["job_id"]:
            problems.append(f"{rec['label']}: job {rec['job_id']} is lost (not in ListJobs)")
        elif job is not None and rec["job_id"] and job.job_id != rec["job_id"]:
            problems.append(f"{rec['label']}: client saw {rec['job_id']}, server {job.job_id}")
        elif job is not None and (rec["job_id"] or rec["outcome"] == "rejected"):
            why = consistent(rec, job)
            if why:
                problems.append(f"{rec['label']} (job {job.job_id}, {rec['kind']}): {why}")
        elif job is not None and job.state != S.JOB_STATE_CANCELLED:
            # Gave up before the first event: the job, if one was made, must be cancelled.
            problems.append(f"{rec['label']}: no id seen, server job {job.job_id} is {column}")

    # The counters moved by exactly the jobs found above; rejections by at least what we saw.
    def delta(outcome):
        key = f'meshd_jobs_total{{outcome="{outcome}"}}'
        return round(after[key] - before[key])
    for outcome, state in (("succeeded", S.JOB_STATE_SUCCEEDED),
                           ("cancelled", S.JOB_STATE_CANCELLED), ("failed", S.JOB_STATE_FAILED)):
        if delta(outcome) != states.get(state, 0):
            problems.append(f'meshd_jobs_total{{outcome="{outcome}"}} moved by {delta(outcome)}, '
                            f"but ListJobs holds {states.get(state, 0)} such jobs of this run")
    rejected = sum(rec["outcome"] == "rejected" for rec in records)
    if delta("rejected") < rejected:
        problems.append(f"meshd_jobs_total{{outcome=\"rejected\"}} moved by {delta('rejected')}, "
                        f"the clients saw {rejected} rejections")
    return problems, table
