"""A single-node Slurm cluster on this machine, for tests/test_slurm.py and for measuring.

Everything it writes (munge key and socket, slurm.conf, state, spool, logs) lives in one
directory; the daemons are started in the foreground (`munged -F`, `slurmctld -D`, `slurmd -D`)
as children of this process and stopped by their PIDs, so that nothing else on the machine (no
system munged or slurmd, another engineer's test cluster) is touched.  Clients reach this cluster
through the environment variable SLURM_CONF (see `SlurmCluster.env`).

As root, with Debian's slurm-wlm and munge (`apt-get install slurm-wlm munge`):

    python3 tests/slurm_cluster.py /tmp/cluster -- snakemake --profile profiles/slurm ...

starts the cluster, runs the command with SLURM_CONF set, and stops the cluster again.
"""

from __future__ import annotations

import os
import shutil
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

DAEMONS = ("munged", "slurmctld", "slurmd")
CLIENTS = ("sbatch", "squeue", "sinfo", "scontrol", "srun", "scancel", "sacct", "sacctmgr")
PARTITION = "main"


def missing_programs() -> list[str]:
    """The programs a cluster needs that are not installed (daemons are in /usr/sbin)."""
    path = os.pathsep.join([os.environ.get("PATH", ""), "/usr/sbin", "/usr/local/sbin"])
    return [p for p in (*DAEMONS, *CLIENTS) if shutil.which(p, path=path) is None]


def _program(name: str) -> str:
    path = os.pathsep.join([os.environ.get("PATH", ""), "/usr/sbin", "/usr/local/sbin"])
    found = shutil.which(name, path=path)
    if found is None:
        raise RuntimeError(f"{name} is not installed (apt-get install slurm-wlm munge)")
    return found


def _free_ports(n: int) -> list[int]:
    socks = []
    try:
        for _ in range(n):
            s = socket.socket()
            s.bind(("127.0.0.1", 0))
            socks.append(s)
        return [s.getsockname()[1] for s in socks]
    finally:
        for s in socks:
            s.close()


def _free_memory_mb() -> int:
    for line in Path("/proc/meminfo").read_text().splitlines():
        if line.startswith("MemAvailable:"):
            return int(line.split()[1]) // 1024
    raise RuntimeError("no MemAvailable in /proc/meminfo")


class SlurmCluster:
    """munged + slurmctld + slurmd under `root`; use as a context manager."""

    def __init__(self, root: Path, cpus: int = 2, scheduler_parameters: str | None = None):
        self.root = Path(root).resolve()
        self.cpus = cpus
        self.scheduler_parameters = scheduler_parameters
        self.node = socket.gethostname().split(".")[0]
        self.procs: dict[str, subprocess.Popen] = {}
        self.conf = self.root / "slurm.conf"
        self.bin = self.root / "bin"
        path = os.pathsep.join([str(self.bin), os.environ.get("PATH", "")])
        self.env = dict(os.environ, SLURM_CONF=str(self.conf), PATH=path)

    # --- configuration -------------------------------------------------------------------------
    def _write_files(self) -> None:
        r = self.root
        for d in ("munge", "state", "spool", "log"):
            (r / d).mkdir(parents=True, exist_ok=True)
        (r / "munge").chmod(0o700)
        key = r / "munge" / "munge.key"
        if not key.exists():
            key.write_bytes(os.urandom(1024))
        key.chmod(0o400)
        ctld_port, d_port = _free_ports(2)
        memory = max(500, int(_free_memory_mb() * 0.8))
        (r / "plugstack.conf").write_text("")
        # Clients that find this cluster without SLURM_CONF: the slurm-jobstep plugin removes
        # every SLURM_* variable (SLURM_CONF too) before its `srun` inside a job.
        self.bin.mkdir(exist_ok=True)
        for name in CLIENTS:
            wrapper = self.bin / name
            wrapper.write_text(f'#!/bin/sh\nSLURM_CONF={self.conf} exec {_program(name)} "$@"\n')
            wrapper.chmod(0o755)
        sched = self.scheduler_parameters
        sched = f"SchedulerParameters={sched}\n" if sched else ""
        self.conf.write_text(
            f"""# single-node test cluster written by tests/slurm_cluster.py
ClusterName=rotbeamtest
SlurmctldHost={self.node}(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket={r}/munge/munge.socket
SlurmctldPort={ctld_port}
SlurmdPort={d_port}
StateSaveLocation={r}/state
SlurmdSpoolDir={r}/spool
SlurmctldPidFile={r}/slurmctld.pid
SlurmdPidFile={r}/slurmd.pid
SlurmctldLogFile={r}/log/slurmctld.log
SlurmdLogFile={r}/log/slurmd.log
PlugStackConfig={r}/plugstack.conf
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
MpiDefault=none
ReturnToService=2
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
MinJobAge=86400
{sched}NodeName={self.node} NodeAddr=127.0.0.1 CPUs={self.cpus} RealMemory={memory} State=UNKNOWN
PartitionName={PARTITION} Nodes={self.node} Default=YES MaxTime=INFINITE State=UP
"""
        )

    # --- lifecycle ---------------------------------------------------------------------------
    def _spawn(self, name: str, args: list[str]) -> None:
        log = open(self.root / "log" / f"{name}.out", "wb")  # noqa: SIM115 (closed with the proc)
        self.procs[name] = subprocess.Popen(
            [_program(name), *args],
            env=self.env,
            stdout=log,
            stderr=subprocess.STDOUT,
            stdin=subprocess.DEVNULL,
            start_new_session=True,
        )
        log.close()

    def _wait(self, what: str, ok, timeout: float) -> None:
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            for name, p in self.procs.items():
                if p.poll() is not None:
                    raise RuntimeError(
                        f"{name} exited with status {p.returncode} while waiting for {what}:\n"
                        + self.logs()
                    )
            if ok():
                return
            time.sleep(0.2)
        raise RuntimeError(f"timed out after {timeout:.0f} s waiting for {what}:\n" + self.logs())

    def start(self, timeout: float = 60) -> SlurmCluster:
        self._write_files()
        m = self.root / "munge"
        self._spawn(
            "munged",
            [
                "-F",
                "--force",
                f"--socket={m}/munge.socket",
                f"--key-file={m}/munge.key",
                f"--pid-file={m}/munged.pid",
                f"--seed-file={m}/munged.seed",
                f"--log-file={self.root}/log/munged.log",
            ],
        )
        self._wait("munged's socket", (m / "munge.socket").exists, timeout)
        self._spawn("slurmctld", ["-D", "-i", "-c"])
        self._wait("slurmctld", lambda: self._run("scontrol", "ping").returncode == 0, timeout)
        self._spawn("slurmd", ["-D"])
        self._wait("the node to come up", self._node_idle, timeout)
        return self

    def _node_idle(self) -> bool:
        p = self._run("sinfo", "-h", "-n", self.node, "-o", "%t")
        return p.returncode == 0 and p.stdout.strip() in ("idle", "mix", "alloc")

    def _run(self, *cmd: str) -> subprocess.CompletedProcess:
        return subprocess.run(
            [_program(cmd[0]), *cmd[1:]], env=self.env, capture_output=True, text=True, timeout=30
        )

    def jobs(self) -> list[dict[str, str]]:
        """Every job this cluster has seen (MinJobAge keeps finished ones for a day)."""
        p = self._run("squeue", "--states=all", "-h", "-o", "%i|%j|%T|%M")
        if p.returncode != 0:
            raise RuntimeError(f"squeue failed: {p.stderr}")
        keys = ("id", "name", "state", "time")
        return [dict(zip(keys, line.split("|"), strict=True)) for line in p.stdout.splitlines()]

    def stop(self) -> None:
        """Cancel what still runs, then end exactly the daemons started here."""
        if "slurmctld" in self.procs and self.procs["slurmctld"].poll() is None:
            self._run("scancel", "--full", "--user", str(os.getuid()))
            end = time.monotonic() + 20
            while time.monotonic() < end and any(
                j["state"] in ("RUNNING", "COMPLETING", "PENDING") for j in self._jobs_or_none()
            ):
                time.sleep(0.5)
        for name in reversed(list(self.procs)):
            p = self.procs[name]
            if p.poll() is None:
                p.send_signal(signal.SIGTERM)
                try:
                    p.wait(timeout=15)
                except subprocess.TimeoutExpired:
                    p.kill()
                    p.wait(timeout=15)
        self.procs.clear()

    def _jobs_or_none(self) -> list[dict[str, str]]:
        try:
            return self.jobs()
        except (RuntimeError, subprocess.TimeoutExpired):
            return []

    def logs(self) -> str:
        out = []
        for f in sorted((self.root / "log").glob("*")):
            text = f.read_text(errors="replace").strip().splitlines()[-15:]
            out.append(f"--- {f.name}\n" + "\n".join(text))
        return "\n".join(out)

    def __enter__(self) -> SlurmCluster:
        try:
            return self.start()
        except BaseException:
            self.stop()
            raise

    def __exit__(self, *exc) -> None:
        self.stop()


def main(argv: list[str]) -> int:
    if "--" not in argv or argv.index("--") != 1:
        print(__doc__.split("As root")[1], file=sys.stderr)
        return 2
    root, cmd = Path(argv[0]), argv[2:]

    def stop(signum, frame):
        raise SystemExit(128 + signum)  # the daemons are stopped on the way out

    signal.signal(signal.SIGTERM, stop)
    with SlurmCluster(root) as cluster:
        print(f"SLURM_CONF={cluster.conf}", file=sys.stderr)
        return subprocess.run(cmd, env=cluster.env).returncode


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
