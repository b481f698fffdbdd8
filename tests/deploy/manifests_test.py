#!/usr/bin/env python3
"""deploy/ agrees with itself and with the server.

Usage: manifests_test.py --repo DIR --haptic-server BIN --hapticctl BIN
       --unit haptic-server.service --defaults haptic-server.default [unittest args]

The systemd unit and its defaults file (packaging/, as the build
configured them) run the server as the user `haptic` with its state
directory and flags it accepts.

The server's command lines (Deployment, Fleet, the Dockerfile's ENTRYPOINT
and CMD, compose), the probes and the load test are read from the files and
checked against each other, against the flags the built binaries accept
(--help), and against what the server does (the Agones label it sets).
Each failure names the file and the field.
"""

import argparse
import json
import os
import re
import shlex
import subprocess
import sys
import unittest

try:
    import yaml
except ImportError:
    sys.exit("FAIL: python3-yaml is missing (scripts/setup.sh installs yamllint, which brings it)")

ARGS = None
SECRET_DIR = "/run/secrets/haptics"
IMAGE_SCENES = "/usr/share/haptics/scenes/"
SCENE_LABEL = "agones.dev/sdk-scene"


# ---------- reading ----------

def rel(path):
    return os.path.relpath(path, ARGS.repo)


def load_yaml(relpath):
    with open(os.path.join(ARGS.repo, relpath), encoding="utf-8") as f:
        return [d for d in yaml.safe_load_all(f) if d is not None]


def one(relpath, kind):
    docs = [d for d in load_yaml(relpath) if d.get("kind") == kind]
    assert len(docs) == 1, f"{relpath}: expected one {kind}, found {len(docs)}"
    return docs[0]


def help_flags(command):
    """{flag: how many values} and {flag: default} from a CLI11 --help."""
    out = subprocess.run(command + ["--help"], capture_output=True, text=True, check=True).stdout
    flags, defaults = {}, {}
    for line in out.splitlines():
        m = re.match(r"[ \t]+(?:-\w,)?(--[a-z0-9-]+)(?: (.*?))?(?:[ \t]{2,}|$)", line)
        if not m:
            continue
        flag, spec = m.group(1), (m.group(2) or "").strip()
        # 0: a switch, 1: one value, 2: one or more (CLI11 writes "TYPE ...").
        flags[flag] = 0 if not re.match(r"[A-Z]", spec) else 2 if spec.split("=")[0].endswith("...") else 1
        if "=" in spec:
            defaults[flag] = spec.rsplit("=", 1)[1]
    return flags, defaults


def parse_args(argv, flags, where, strict=True):
    """[(flag, value or None)] of a command line; unknown flags fail, or
    (strict=False) are taken to have one value when one follows."""
    out, i = [], 0
    while i < len(argv):
        word = argv[i]
        if not word.startswith("--"):
            raise AssertionError(f"{where}: '{word}' is no flag (a flag's value without its flag?)")
        flag, _, inline = word.partition("=")
        if flag not in flags:
            if strict:
                raise AssertionError(f"{where}: {flag} is not a flag of this binary (--help)")
            flags = dict(flags, **{flag: int(i + 1 < len(argv) and not argv[i + 1].startswith("--"))})
        if flags[flag] and not inline:
            i += 1
            if i == len(argv) or argv[i].startswith("--"):
                raise AssertionError(f"{where}: {flag} has no value")
            out.append((flag, argv[i]))
            while flags[flag] == 2 and i + 1 < len(argv) and not argv[i + 1].startswith("--"):
                i += 1
                out.append((flag, argv[i]))
        else:
            out.append((flag, inline or None))
        i += 1
    return out


def values(parsed, flag):
    return [v for f, v in parsed if f == flag]


def value(parsed, flag, where):
    v = values(parsed, flag)
    assert len(v) == 1, f"{where}: expected {flag} once, found {len(v)}"
    return v[0]


def cpus(quantity):
    """A Kubernetes CPU quantity in CPUs: "2" -> 2, "1500m" -> 1.5."""
    q = str(quantity)
    return int(q[:-1]) / 1000 if q.endswith("m") else float(q)


def port_of(address):
    return int(address.rsplit(":", 1)[1])


def label_value(text):
    """server/agones/agones_sdk.cc AgonesLabelValue."""
    value = ""
    for c in text.lower():
        if c.isascii() and (c.isalnum() or c in "._-"):
            value += c
        elif not value.endswith("-"):
            value += "-"
    value = value[:63]
    return value.strip("._-")


def scene_name(image_path, where):
    assert image_path.startswith(IMAGE_SCENES), f"{where}: --scene {image_path} is not in {IMAGE_SCENES}"
    path = os.path.join(ARGS.repo, "scenes", image_path[len(IMAGE_SCENES):])
    assert os.path.isfile(path), f"{where}: --scene {image_path}: {rel(path)} does not exist"
    m = re.search(r'^name:\s*"([^"]*)"', open(path, encoding="utf-8").read(), re.M)
    assert m, f"{rel(path)}: no top-level name"
    return m.group(1)


class Dockerfile:
    def __init__(self, relpath):
        self.relpath = relpath
        text = open(os.path.join(ARGS.repo, relpath), encoding="utf-8").read()
        lines = [l for l in text.splitlines() if not l.lstrip().startswith("#")]
        joined = re.sub(r"\\\n", " ", "\n".join(lines))
        runtime = re.split(r"(?im)^FROM\s", joined)[-1]
        self.instructions = [(m.group(1).upper(), m.group(2).strip())
                             for m in re.finditer(r"(?m)^([A-Za-z]+)\s+(.*)$", runtime)]

    def last(self, name):
        found = [v for n, v in self.instructions if n == name]
        assert found, f"{self.relpath}: no {name} in the runtime stage"
        return found[-1]

    def exec_form(self, name):
        v = self.last(name)
        try:
            return json.loads(v)
        except ValueError:
            raise AssertionError(f"{self.relpath}: {name} is not in exec form (a JSON array)")

    def expose(self):
        return {int(p.split("/")[0]) for p in self.last("EXPOSE").split()}

    def user(self):
        uid, _, gid = self.last("USER").partition(":")
        assert uid.isdigit(), f"{self.relpath}: USER {uid}: give the numeric id (runAsNonRoot checks it)"
        return int(uid), int(gid) if gid else None

    def env(self, key):
        for n, v in self.instructions:
            if n == "ENV":
                m = re.search(rf"(?:^|\s){key}=(\S+)", v)
                if m:
                    return m.group(1).strip('"')
        return None

    def healthcheck_command(self):
        v = self.last("HEALTHCHECK")
        m = re.search(r"\bCMD\s+(.*)$", v)
        assert m, f"{self.relpath}: HEALTHCHECK has no CMD"
        return m.group(1)


class Server:
    """One haptic-server command line and the container it runs in."""

    def __init__(self, where, argv, container=None, pod=None, pod_meta=None):
        self.where = where
        self.argv = argv
        self.container = container
        self.pod = pod
        self.pod_meta = pod_meta
        # Unknown flags fail test_every_server_flag_is_in_help alone.
        self.parsed = parse_args(argv, SERVER_FLAGS, where + " args", strict=False)

    def flag(self, name):
        return value(self.parsed, name, self.where + " args")

    def has(self, name):
        return bool(values(self.parsed, name))

    def container_port(self, name):
        for p in self.container.get("ports", []):
            if p.get("name") == name:
                return p["containerPort"]
        return None


def k8s_server():
    d = one("deploy/k8s/deployment.yaml", "Deployment")
    pod = d["spec"]["template"]["spec"]
    c = pod["containers"][0]
    return Server("deploy/k8s/deployment.yaml: spec.template.spec.containers[haptic-server]",
                  c["command"][1:] + c["args"], c, pod, d["spec"]["template"]["metadata"])


def fleet_server():
    f = one("deploy/agones/fleet.yaml", "Fleet")
    gs = f["spec"]["template"]["spec"]
    pod = gs["template"]["spec"]
    name = gs.get("container") or pod["containers"][0]["name"]
    c = next(c for c in pod["containers"] if c["name"] == name)
    return Server(f"deploy/agones/fleet.yaml: spec.template.spec.template.spec.containers[{name}]",
                  c["command"][1:] + c["args"], c, pod, gs["template"]["metadata"])


def docker_server(cmd=None):
    df = Dockerfile("deploy/docker/Dockerfile")
    entry = df.exec_form("ENTRYPOINT")
    cmd = df.exec_form("CMD") if cmd is None else cmd
    return Server("deploy/docker/Dockerfile: ENTRYPOINT + CMD", entry[1:] + cmd)


def compose():
    return load_yaml("deploy/docker/compose.yaml")[0]


def compose_server():
    svc = compose()["services"]["server"]
    df = Dockerfile("deploy/docker/Dockerfile")
    return Server("deploy/docker/compose.yaml: services.server.command (after the ENTRYPOINT)",
                  df.exec_form("ENTRYPOINT")[1:] + svc["command"])


def servers_in_pods():
    return [k8s_server(), fleet_server()]


def all_servers():
    return servers_in_pods() + [docker_server(), compose_server()]


def probes(server):
    for kind in ("startupProbe", "readinessProbe", "livenessProbe"):
        if kind in server.container:
            yield kind, server.container[kind]


def health_probe_args(server, kind, probe):
    where = f"{server.where}.{kind}.exec.command"
    command = probe.get("exec", {}).get("command")
    assert command, f"{where}: not an exec probe"
    assert command[:2] == ["/usr/bin/hapticctl", "health"], \
        f"{where}: expected /usr/bin/hapticctl health, found {command[:2]}"
    return where, parse_args(command[2:], HEALTH_FLAGS, where)


# ---------- checks ----------

class ServerFlags(unittest.TestCase):
    def test_every_server_flag_is_in_help(self):
        for s in all_servers():
            parse_args(s.argv, SERVER_FLAGS, s.where + " args")

    def test_probe_and_healthcheck_flags_are_in_hapticctl_health_help(self):
        for s in servers_in_pods():
            for kind, probe in probes(s):
                health_probe_args(s, kind, probe)
        df = Dockerfile("deploy/docker/Dockerfile")
        for words in healthcheck_health_calls(df):
            parse_args(words, HEALTH_FLAGS, f"{df.relpath}: HEALTHCHECK hapticctl health")

    def test_loadtest_flags_are_in_hapticctl_loadtest_help(self):
        svc = compose()["services"]["loadtest"]
        where = "deploy/docker/compose.yaml: services.loadtest.command"
        self.assertEqual(svc["entrypoint"], ["/usr/bin/hapticctl"], where)
        self.assertEqual(svc["command"][0], "loadtest", where)
        parse_args(svc["command"][1:], LOADTEST_FLAGS, where)

    def test_containers_listen_on_every_address(self):
        for s in all_servers():
            self.assertTrue(s.flag("--listen").startswith("0.0.0.0:"), f"{s.where}: --listen {s.flag('--listen')}")
            self.assertTrue(s.flag("--metrics").startswith("0.0.0.0:"), f"{s.where}: --metrics")

    def test_tls_or_explicitly_insecure(self):
        # The server refuses a non-loopback --listen without TLS unless
        # --insecure-listen; with TLS, cert and key go together.
        for s in all_servers():
            tls = s.has("--tls-cert")
            self.assertEqual(tls, s.has("--tls-key"), f"{s.where}: --tls-cert and --tls-key go together")
            self.assertTrue(tls or s.has("--insecure-listen"),
                            f"{s.where}: no TLS and no --insecure-listen: the server refuses to start")
            self.assertFalse(tls and s.has("--insecure-listen"), f"{s.where}: TLS and --insecure-listen")
        for s in servers_in_pods() + [docker_server()]:
            self.assertTrue(s.has("--tls-cert") and s.has("--tokens"), f"{s.where}: TLS and tokens expected")

    def test_threads_per_scene_within_the_cpu_limit(self):
        for s in servers_in_pods():
            cpu = cpus(s.container["resources"]["limits"]["cpu"])
            threads = int(s.flag("--threads-per-scene"))
            self.assertLessEqual(threads, cpu, f"{s.where}: --threads-per-scene {threads} > limits.cpu {cpu}")


class Ports(unittest.TestCase):
    def test_container_ports_match_listen_and_metrics(self):
        k = k8s_server()
        self.assertEqual(k.container_port("grpc"), port_of(k.flag("--listen")),
                         f"{k.where}.ports[grpc].containerPort vs --listen")
        f = fleet_server()
        fleet = one("deploy/agones/fleet.yaml", "Fleet")
        grpc = [p for p in fleet["spec"]["template"]["spec"]["ports"] if p["name"] == "grpc"]
        self.assertEqual(len(grpc), 1, "deploy/agones/fleet.yaml: spec.template.spec.ports[grpc]")
        self.assertEqual(grpc[0]["containerPort"], port_of(f.flag("--listen")),
                         "deploy/agones/fleet.yaml: spec.template.spec.ports[grpc].containerPort vs --listen")
        for s in (k, f):
            self.assertEqual(s.container_port("metrics"), port_of(s.flag("--metrics")),
                             f"{s.where}.ports[metrics].containerPort vs --metrics")

    def test_service_target_ports(self):
        k = k8s_server()
        svc = one("deploy/k8s/service.yaml", "Service")
        by_name = {p["name"]: p for p in svc["spec"]["ports"]}
        for name, flag in (("grpc", "--listen"), ("metrics", "--metrics")):
            self.assertIn(name, by_name, f"deploy/k8s/service.yaml: spec.ports[{name}]")
            target = by_name[name]["targetPort"]
            if isinstance(target, str):
                target = k.container_port(target)
            self.assertEqual(target, port_of(k.flag(flag)),
                             f"deploy/k8s/service.yaml: spec.ports[{name}].targetPort vs {flag}")

    def test_probes_ask_the_listen_port(self):
        for s in servers_in_pods():
            for kind, probe in probes(s):
                where, parsed = health_probe_args(s, kind, probe)
                address = value(parsed, "--server", where)
                self.assertTrue(address.startswith("127.0.0.1:"), f"{where}: --server {address}")
                self.assertEqual(port_of(address), port_of(s.flag("--listen")), f"{where}: --server vs --listen")

    def test_prometheus_annotations(self):
        for s in servers_in_pods():
            a = s.pod_meta.get("annotations", {})
            where = s.where.split(":")[0] + ": pod template metadata.annotations"
            self.assertEqual(a.get("prometheus.io/scrape"), "true", f"{where}[prometheus.io/scrape]")
            self.assertEqual(a.get("prometheus.io/port"), str(port_of(s.flag("--metrics"))),
                             f"{where}[prometheus.io/port] vs --metrics")
            self.assertEqual(a.get("prometheus.io/path"), "/metrics", f"{where}[prometheus.io/path]")

    def test_dockerfile_expose_and_healthcheck(self):
        df = Dockerfile("deploy/docker/Dockerfile")
        d = docker_server()
        ports = {port_of(d.flag("--listen")), port_of(d.flag("--metrics"))}
        self.assertEqual(df.expose(), ports, f"{df.relpath}: EXPOSE vs --listen and --metrics")
        for s in servers_in_pods():
            self.assertEqual({port_of(s.flag("--listen")), port_of(s.flag("--metrics"))}, ports,
                             f"{s.where}: ports differ from the Dockerfile's EXPOSE")
        for words in healthcheck_health_calls(df):
            parsed = parse_args(words, HEALTH_FLAGS, f"{df.relpath}: HEALTHCHECK")
            self.assertEqual(value(parsed, "--server", df.relpath), f"127.0.0.1:{port_of(d.flag('--listen'))}",
                             f"{df.relpath}: HEALTHCHECK --server vs --listen")

    def test_compose_ports_and_loadtest_target(self):
        c = compose()
        s = compose_server()
        df = Dockerfile("deploy/docker/Dockerfile")
        for mapping in c["services"]["server"]["ports"]:
            container_port = int(str(mapping).rsplit(":", 1)[1])
            self.assertIn(container_port, df.expose(), f"deploy/docker/compose.yaml: services.server.ports {mapping}")
        parsed = parse_args(c["services"]["loadtest"]["command"][1:], LOADTEST_FLAGS, "loadtest")
        target = value(parsed, "--server", "deploy/docker/compose.yaml: services.loadtest")
        self.assertEqual(target, f"server:{port_of(s.flag('--listen'))}",
                         "deploy/docker/compose.yaml: services.loadtest --server vs the server's --listen")
        self.assertTrue(values(parsed, "--allow-remote"),
                        "deploy/docker/compose.yaml: services.loadtest: a server off loopback needs --allow-remote")


class Workload(unittest.TestCase):
    def test_deployment_selector_matches_template_and_service(self):
        d = one("deploy/k8s/deployment.yaml", "Deployment")
        selector = d["spec"]["selector"]["matchLabels"]
        labels = d["spec"]["template"]["metadata"]["labels"]
        for k, v in selector.items():
            self.assertEqual(labels.get(k), v, f"deploy/k8s/deployment.yaml: spec.selector.matchLabels[{k}] "
                                               "vs spec.template.metadata.labels")
        svc = one("deploy/k8s/service.yaml", "Service")
        for k, v in svc["spec"]["selector"].items():
            self.assertEqual(labels.get(k), v, f"deploy/k8s/service.yaml: spec.selector[{k}] "
                                               "vs the Deployment's template labels")
        self.assertEqual(d["spec"]["replicas"], 1, "deploy/k8s/deployment.yaml: spec.replicas (one state volume)")

    def test_guaranteed_qos_in_whole_cpus(self):
        for s in servers_in_pods():
            r = s.container["resources"]
            where = f"{s.where}.resources"
            self.assertEqual(r["requests"], r["limits"], f"{where}: requests != limits (not Guaranteed)")
            self.assertEqual(set(r["limits"]), {"cpu", "memory"}, f"{where}.limits")
            cpu = str(r["limits"]["cpu"])
            self.assertTrue(cpu.isdigit() and int(cpu) >= 1, f"{where}.limits.cpu {cpu}: whole CPUs")

    def test_same_resources_probe_and_secret_everywhere(self):
        k, f = servers_in_pods()
        self.assertEqual(k.container["resources"], f.container["resources"], f"{f.where}.resources vs {k.where}")
        self.assertEqual(k.container["readinessProbe"], f.container["readinessProbe"],
                         f"{f.where}.readinessProbe vs {k.where}")
        ks = [v["secret"] for v in k.pod["volumes"] if "secret" in v]
        fs = [v["secret"] for v in f.pod["volumes"] if "secret" in v]
        self.assertEqual(ks, fs, f"{f.where.split(':')[0]}: secret volume vs deploy/k8s/deployment.yaml")
        for flag in ("--tls-cert", "--tls-key", "--tokens", "--scene", "--max-clients", "--threads-per-scene"):
            self.assertEqual(values(k.parsed, flag), values(f.parsed, flag), f"{f.where}: {flag} differs from k8s")

    def test_volume_mounts_refer_to_volumes(self):
        for s in servers_in_pods():
            names = [v["name"] for v in s.pod.get("volumes", [])]
            self.assertEqual(len(names), len(set(names)), f"{s.where}: volume names repeat")
            for m in s.container.get("volumeMounts", []):
                self.assertIn(m["name"], names, f"{s.where}.volumeMounts[{m['name']}]: no such volume")

    def test_written_paths_are_on_volumes(self):
        # readOnlyRootFilesystem: --state-dir, --record-dir and /tmp must be mounted.
        for s in servers_in_pods():
            self.assertTrue(s.container["securityContext"]["readOnlyRootFilesystem"], s.where)
            mounts = [m["mountPath"] for m in s.container["volumeMounts"] if not m.get("readOnly")]
            for path in [s.flag("--state-dir"), "/tmp"] + values(s.parsed, "--record-dir"):
                self.assertTrue(any(path == m or path.startswith(m.rstrip("/") + "/") for m in mounts),
                                f"{s.where}: {path} is on no writable volumeMount")

    def test_state_on_the_persistent_volume_claim(self):
        k = k8s_server()
        pvc = one("deploy/k8s/pvc.yaml", "PersistentVolumeClaim")
        vol = next(v for v in k.pod["volumes"] if "persistentVolumeClaim" in v)
        self.assertEqual(vol["persistentVolumeClaim"]["claimName"], pvc["metadata"]["name"],
                         f"{k.where}: volumes[{vol['name']}].persistentVolumeClaim.claimName vs deploy/k8s/pvc.yaml")
        mount = next(m for m in k.container["volumeMounts"] if m["name"] == vol["name"])
        self.assertTrue(k.flag("--state-dir").startswith(mount["mountPath"].rstrip("/") + "/"),
                        f"{k.where}: --state-dir is not on the claim (mounted at {mount['mountPath']})")
        d = one("deploy/k8s/deployment.yaml", "Deployment")
        self.assertEqual(d["spec"]["strategy"]["type"], "Recreate",
                         "deploy/k8s/deployment.yaml: spec.strategy.type (one writer of the state volume)")

    def test_secret_files_match_the_secret(self):
        df = Dockerfile("deploy/docker/Dockerfile")
        for s in servers_in_pods():
            vol = next(v for v in s.pod["volumes"] if "secret" in v)
            mount = next(m for m in s.container["volumeMounts"] if m["name"] == vol["name"])
            where = f"{s.where}: volumes[{vol['name']}].secret.items"
            self.assertEqual(mount["mountPath"], SECRET_DIR, f"{s.where}.volumeMounts[{vol['name']}].mountPath")
            self.assertTrue(mount.get("readOnly"), f"{s.where}.volumeMounts[{vol['name']}].readOnly")
            items = {i["path"] for i in vol["secret"].get("items", [])}
            self.assertTrue(items, f"{where}: list the files")
            used = [v for f, v in s.parsed if v and v.startswith(SECRET_DIR + "/")]
            for _, probe in probes(s):
                used += [w for w in probe["exec"]["command"] if w.startswith(SECRET_DIR + "/")]
            for path in used:
                self.assertIn(os.path.basename(path), items, f"{where}: no {os.path.basename(path)} for {path}")
            for item in items:
                self.assertIn(f"{SECRET_DIR}/{item}", used, f"{where}: {item} is used by nothing")
            # The image's default command and health check read the same files.
            docker_used = [v for f, v in docker_server().parsed if v and v.startswith(SECRET_DIR + "/")]
            docker_used += re.findall(re.escape(SECRET_DIR) + r"/[\w.]+", df.healthcheck_command())
            for path in docker_used:
                self.assertIn(os.path.basename(path), items, f"{df.relpath}: {path} is not in {where}")

    def test_tls_server_name_is_the_service_name(self):
        svc = one("deploy/k8s/service.yaml", "Service")["metadata"]["name"]
        df = Dockerfile("deploy/docker/Dockerfile")
        self.assertEqual(df.env("HAPTIC_TLS_SERVER_NAME"), svc, f"{df.relpath}: ENV HAPTIC_TLS_SERVER_NAME")
        for s in servers_in_pods():
            for kind, probe in probes(s):
                where, parsed = health_probe_args(s, kind, probe)
                self.assertEqual(value(parsed, "--tls-server-name", where), svc, f"{where}: --tls-server-name")
                self.assertEqual(value(parsed, "--tls-ca", where), f"{SECRET_DIR}/ca.crt", f"{where}: --tls-ca")

    def test_non_root_user_of_the_image(self):
        df = Dockerfile("deploy/docker/Dockerfile")
        uid, gid = df.user()
        self.assertNotEqual(uid, 0, f"{df.relpath}: USER")
        for s in servers_in_pods():
            sc = s.pod["securityContext"]
            where = f"{s.where.split(':')[0]}: pod securityContext"
            self.assertTrue(sc.get("runAsNonRoot"), f"{where}.runAsNonRoot")
            self.assertEqual(sc.get("runAsUser"), uid, f"{where}.runAsUser vs {df.relpath} USER")
            if gid is not None:
                self.assertEqual(sc.get("runAsGroup"), gid, f"{where}.runAsGroup vs {df.relpath} USER")

    def test_termination_grace_covers_the_drain(self):
        # Drain: one last step, then 2 s for gRPC; the recorder syncs every 100 ms.
        for s in servers_in_pods():
            self.assertGreaterEqual(s.pod.get("terminationGracePeriodSeconds", 30), 10,
                                    f"{s.where.split(':')[0]}: terminationGracePeriodSeconds")
        grace = compose()["services"]["server"].get("stop_grace_period", "10s")
        self.assertGreaterEqual(int(grace.rstrip("s")), 10, "deploy/docker/compose.yaml: stop_grace_period")

    def test_scenes_exist(self):
        for s in all_servers():
            for path in values(s.parsed, "--scene"):
                scene_name(path, s.where)

    def test_compose_state_on_a_named_volume(self):
        c = compose()
        s = compose_server()
        mounts = [str(v).split(":") for v in c["services"]["server"]["volumes"]]
        state = s.flag("--state-dir")
        named = [m for m in mounts if m[0] in c.get("volumes", {}) and state.startswith(m[1].rstrip("/") + "/")]
        self.assertTrue(named, f"deploy/docker/compose.yaml: services.server.volumes: --state-dir {state} "
                               "is on no named volume")


class Image(unittest.TestCase):
    def test_dockerfile_stages(self):
        relpath = "deploy/docker/Dockerfile"
        text = open(os.path.join(ARGS.repo, relpath), encoding="utf-8").read()
        joined = re.sub(r"\\\n", " ", "\n".join(l for l in text.splitlines() if not l.lstrip().startswith("#")))
        froms = re.findall(r"(?im)^FROM\s+(.*)$", joined)
        self.assertEqual([f.split()[0] for f in froms], ["debian:12", "debian:12-slim"], f"{relpath}: FROM lines")
        build = re.split(r"(?im)^FROM\s", joined)[1]
        self.assertIn("scripts/setup.sh", build, f"{relpath}: the build stage does not run scripts/setup.sh")
        self.assertRegex(build, r"-G Ninja", f"{relpath}: the build stage does not use Ninja")
        self.assertRegex(build, r"CMAKE_BUILD_TYPE=Release", f"{relpath}: the build stage does not build Release")
        # The build stage makes the Debian packages; the runtime installs
        # haptic-server's (haptic-server and haptic-import, which it starts
        # from its own folder, in /usr/bin) and hapticctl's.
        self.assertIn("cpack -G DEB", build, f"{relpath}: the build stage makes no Debian packages")
        self.assertIn("-DCMAKE_INSTALL_PREFIX=/usr", build, f"{relpath}: the packages are not for /usr")
        runtime = re.split(r"(?im)^FROM\s", joined)[-1]
        for package in ("haptic-server", "hapticctl"):
            self.assertRegex(runtime, rf"apt-get install[^&]*/{package}_\S*\.deb",
                             f"{relpath}: the runtime does not install the {package} package")
        entry = Dockerfile(relpath).exec_form("ENTRYPOINT")[0]
        self.assertEqual(entry, "/usr/bin/haptic-server", f"{relpath}: ENTRYPOINT, where the package puts it")


class Agones(unittest.TestCase):
    def test_api_versions(self):
        for path, kind, version in (("deploy/agones/fleet.yaml", "Fleet", "agones.dev/v1"),
                                    ("deploy/agones/fleetautoscaler.yaml", "FleetAutoscaler",
                                     "autoscaling.agones.dev/v1"),
                                    ("deploy/agones/allocation.yaml", "GameServerAllocation",
                                     "allocation.agones.dev/v1"),
                                    ("deploy/k8s/deployment.yaml", "Deployment", "apps/v1")):
            self.assertEqual(one(path, kind)["apiVersion"], version, f"{path}: apiVersion")

    def test_health_period_holds_two_pings(self):
        f = fleet_server()
        health = one("deploy/agones/fleet.yaml", "Fleet")["spec"]["template"]["spec"]["health"]
        where = "deploy/agones/fleet.yaml: spec.template.spec.health"
        interval = float((values(f.parsed, "--agones-health-interval-s") or
                          [SERVER_DEFAULTS["--agones-health-interval-s"]])[0])
        self.assertFalse(health.get("disabled", False), f"{where}.disabled")
        self.assertGreaterEqual(health["periodSeconds"], 2 * interval,
                                f"{where}.periodSeconds {health['periodSeconds']} holds fewer than 2 pings "
                                f"of --agones-health-interval-s {interval}")
        self.assertGreaterEqual(health["failureThreshold"], 1, f"{where}.failureThreshold")
        self.assertGreaterEqual(health["initialDelaySeconds"], 1, f"{where}.initialDelaySeconds")

    def test_agones_health_checking_is_left_on(self):
        # Agones starts its health checking from the liveness probe it adds on
        # /gshealthz, and adds it only when the container has none.
        f = fleet_server()
        self.assertNotIn("livenessProbe", f.container, f"{f.where}.livenessProbe")

    def test_game_port(self):
        fleet = one("deploy/agones/fleet.yaml", "Fleet")
        gs = fleet["spec"]["template"]["spec"]
        grpc = next(p for p in gs["ports"] if p["name"] == "grpc")
        where = "deploy/agones/fleet.yaml: spec.template.spec.ports[grpc]"
        self.assertIn(grpc["portPolicy"], ("Dynamic",), f"{where}.portPolicy (the server's --listen port is fixed)")
        self.assertEqual(grpc.get("protocol"), "TCP", f"{where}.protocol (gRPC is TCP; Agones defaults to UDP)")
        names = [c["name"] for c in gs["template"]["spec"]["containers"]]
        self.assertIn(gs["container"], names, "deploy/agones/fleet.yaml: spec.template.spec.container")

    def test_scene_label_of_fleet_and_allocation(self):
        f = fleet_server()
        fleet = one("deploy/agones/fleet.yaml", "Fleet")
        scene = label_value(scene_name(f.flag("--scene"), f.where))
        template_labels = fleet["spec"]["template"]["metadata"]["labels"]
        self.assertIn(scene, template_labels.values(),
                      f"deploy/agones/fleet.yaml: spec.template.metadata.labels has no '{scene}' (the scene's label)")
        gsa = one("deploy/agones/allocation.yaml", "GameServerAllocation")
        selectors = gsa["spec"]["selectors"]
        where = "deploy/agones/allocation.yaml: spec.selectors"
        self.assertEqual(len(selectors), 2, where)
        self.assertEqual(selectors[0].get("gameServerState"), "Allocated", f"{where}[0].gameServerState")
        self.assertEqual(selectors[0]["matchLabels"], {SCENE_LABEL: scene},
                         f"{where}[0].matchLabels: the label the server sets is {SCENE_LABEL}: {scene}")
        self.assertEqual(selectors[1].get("gameServerState", "Ready"), "Ready", f"{where}[1].gameServerState")
        for k, v in selectors[1]["matchLabels"].items():
            self.assertEqual(template_labels.get(k), v, f"{where}[1].matchLabels[{k}] vs the Fleet's template labels")

    def test_label_value_matches_the_server(self):
        # The cases of server/agones/agones_sdk.h.
        self.assertEqual(label_value("probe on torus"), "probe-on-torus")
        self.assertEqual(label_value("  Peg  in Hole!! "), "peg-in-hole")
        self.assertEqual(len(label_value("x" * 80)), 63)

    def test_autoscaler_buffer(self):
        fleet = one("deploy/agones/fleet.yaml", "Fleet")
        fas = one("deploy/agones/fleetautoscaler.yaml", "FleetAutoscaler")
        where = "deploy/agones/fleetautoscaler.yaml: spec"
        self.assertEqual(fas["spec"]["fleetName"], fleet["metadata"]["name"], f"{where}.fleetName")
        self.assertEqual(fas["spec"]["policy"]["type"], "Buffer", f"{where}.policy.type")
        b = fas["spec"]["policy"]["buffer"]
        self.assertGreaterEqual(b["minReplicas"], b["bufferSize"], f"{where}.policy.buffer.minReplicas < bufferSize")
        self.assertGreater(b["maxReplicas"], b["minReplicas"], f"{where}.policy.buffer.maxReplicas")


def unit_entries(path):
    """{(section, key): value} of a systemd unit file."""
    entries, section = {}, None
    with open(path, encoding="utf-8") as f:
        for line in f:
            line = line.strip()
            if not line or line.startswith("#"):
                continue
            if line.startswith("["):
                section = line.strip("[]")
                continue
            key, _, val = line.partition("=")
            entries[(section, key)] = val
    return entries


class SystemdUnit(unittest.TestCase):
    """The unit and defaults file of the Debian packages (written for /usr
    by packaging/unit_files.cmake when the build is configured)."""

    def test_runs_as_haptic_with_its_state_dir(self):
        unit = unit_entries(ARGS.unit)
        where = rel(ARGS.unit) if ARGS.unit.startswith(ARGS.repo) else os.path.basename(ARGS.unit)
        self.assertEqual(unit[("Service", "User")], "haptic", f"{where}: User")
        self.assertEqual(unit[("Service", "Group")], "haptic", f"{where}: Group")
        argv = shlex.split(unit[("Service", "ExecStart")])
        self.assertTrue(argv[0].endswith("/bin/haptic-server"), f"{where}: ExecStart {argv[0]}")
        self.assertEqual(argv[-1], "$HAPTIC_SERVER_ARGS", f"{where}: ExecStart ends with the defaults' flags")
        parsed = parse_args(argv[1:-1], SERVER_FLAGS, f"{where}: ExecStart")
        self.assertEqual(value(parsed, "--state-dir", where), "/var/lib/haptic-server")
        # systemd makes /var/lib/<StateDirectory> the user's.
        self.assertEqual(unit[("Service", "StateDirectory")], "haptic-server", f"{where}: StateDirectory")
        self.assertTrue(unit[("Service", "EnvironmentFile")].lstrip("-").endswith("/default/haptic-server"),
                        f"{where}: EnvironmentFile")
        postinst = os.path.join(ARGS.repo, "packaging/debian/haptic-server/postinst")
        with open(postinst, encoding="utf-8") as f:
            self.assertRegex(f.read(), r"adduser --system --group [^\n]*\\\n[^\n]* haptic\b",
                             f"{rel(postinst)}: creates the system user haptic")

    def test_defaults_are_server_flags(self):
        with open(ARGS.defaults, encoding="utf-8") as f:
            m = re.search(r'^HAPTIC_SERVER_ARGS="([^"]*)"$', f.read(), re.MULTILINE)
        self.assertTrue(m, f"{ARGS.defaults}: no HAPTIC_SERVER_ARGS=\"...\"")
        parsed = parse_args(shlex.split(m.group(1)), SERVER_FLAGS, "HAPTIC_SERVER_ARGS")
        for scene in values(parsed, "--scene"):
            name = scene.rsplit("/haptics/scenes/", 1)[-1]
            self.assertTrue(os.path.exists(os.path.join(ARGS.repo, "scenes", name)),
                            f"HAPTIC_SERVER_ARGS: --scene {scene} is not one of scenes/")


def healthcheck_health_calls(df):
    """The hapticctl health command lines of the HEALTHCHECK, with TLS on
    (the secret folder mounted) and off; $HAPTIC_TLS_SERVER_NAME expanded."""
    script = df.healthcheck_command().replace("$HAPTIC_TLS_SERVER_NAME", df.env("HAPTIC_TLS_SERVER_NAME") or "")
    tls = re.search(r'tls="(--[^"]*)"', script)
    m = re.search(r"hapticctl health (.*?) \$tls", script)
    assert m and tls, f"{df.relpath}: HEALTHCHECK: expected 'hapticctl health ... $tls' and tls=\"--...\""
    base = shlex.split(m.group(1))
    return [base, base + shlex.split(tls.group(1))]


def main():
    global ARGS, SERVER_FLAGS, SERVER_DEFAULTS, HEALTH_FLAGS, LOADTEST_FLAGS
    parser = argparse.ArgumentParser()
    parser.add_argument("--repo", required=True)
    parser.add_argument("--haptic-server", required=True)
    parser.add_argument("--hapticctl", required=True)
    parser.add_argument("--unit", required=True, help="the configured haptic-server.service")
    parser.add_argument("--defaults", required=True, help="the configured /etc/default/haptic-server")
    ARGS, rest = parser.parse_known_args()
    for binary in (ARGS.haptic_server, ARGS.hapticctl):
        if not os.path.exists(binary):
            sys.exit(f"FAIL: {binary} is not built (cmake --build build)")
    SERVER_FLAGS, SERVER_DEFAULTS = help_flags([ARGS.haptic_server])
    HEALTH_FLAGS, _ = help_flags([ARGS.hapticctl, "health"])
    LOADTEST_FLAGS, _ = help_flags([ARGS.hapticctl, "loadtest"])
    unittest.main(argv=[sys.argv[0], "-v"] + rest)


if __name__ == "__main__":
    main()
