#!/usr/bin/env python3
"""Checks scripts/k8s/sweep-job.yaml without a cluster: it parses as YAML, is an Indexed Job with
per-index retries, runs `tumble sweep --shards N` with N = completions, writes OUT into the
shared volume, and that volume's claim is ReadWriteMany (every pod writes into it)."""
import sys

import yaml

path = sys.argv[1]
docs = [d for d in yaml.safe_load_all(open(path)) if d]
kinds = {d["kind"]: d for d in docs}
problems = []
job, claim = kinds.get("Job"), kinds.get("PersistentVolumeClaim")
if not job or not claim:
    sys.exit(f"{path}: needs a Job and a PersistentVolumeClaim, has {sorted(kinds)}")
spec = job["spec"]
pod = spec["template"]["spec"]
container = pod["containers"][0]
command = container["command"]
if spec.get("completionMode") != "Indexed":
    problems.append("completionMode must be Indexed (JOB_COMPLETION_INDEX is the shard)")
if "backoffLimitPerIndex" not in spec:
    problems.append("backoffLimitPerIndex: each shard retries on its own")
if pod.get("restartPolicy") != "Never":
    problems.append("restartPolicy must be Never with backoffLimitPerIndex")
if command[:2] != ["tumble", "sweep"]:
    problems.append(f"the container must run tumble sweep, runs {command}")
if "--shards" not in command or command[command.index("--shards") + 1] != str(spec["completions"]):
    problems.append("--shards N must equal completions")
if spec.get("parallelism", 1) > spec["completions"]:
    problems.append("parallelism above completions")
out = command[command.index("--out") + 1] if "--out" in command else ""
mounts = [m["mountPath"] for m in container.get("volumeMounts", [])]
if not any(out.startswith(m.rstrip("/") + "/") for m in mounts):
    problems.append(f"--out {out!r} is not on a mounted volume {mounts}")
claims = [v["persistentVolumeClaim"]["claimName"] for v in pod.get("volumes", [])
          if "persistentVolumeClaim" in v]
if claim["metadata"]["name"] not in claims:
    problems.append("the Job does not mount the claim")
if "ReadWriteMany" not in claim["spec"]["accessModes"]:
    problems.append("the claim must be ReadWriteMany: every pod writes into OUT")
for p in problems:
    print(f"{path}: {p}", file=sys.stderr)
sys.exit(1 if problems else 0)
