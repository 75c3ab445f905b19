#!/usr/bin/python3
"""Checks deploy/kubernetes without a cluster: the manifests parse, agree with
each other, with the Dockerfile and with scallopd's configuration (ports,
probes, user, memory against the cache budget, grace against drain), and the
ConfigMap's scallopd.yaml starts a real scallopd serving the worlds it names.

Usage: kubernetes_manifest_test.py MANIFEST DOCKERFILE SCALLOPD SCALLOP_CLI
"""
import json
import os
import re
import subprocess
import sys
import tempfile
import time

import yaml


def fail(message):
    print(f"kubernetes manifests: {message}", file=sys.stderr)
    sys.exit(1)


def port_of(address):
    return int(address.rsplit(":", 1)[1])


def mebibytes(quantity):
    units = {"Mi": 1, "Gi": 1024}
    match = re.fullmatch(r"(\d+)(Mi|Gi)", quantity)
    if not match:
        fail(f"memory quantity {quantity!r}: use Mi or Gi")
    return int(match.group(1)) * units[match.group(2)]


def check_structure(documents, dockerfile):
    by_kind = {}
    for document in documents:
        by_kind.setdefault(document["kind"], []).append(document)
    for kind in ("ConfigMap", "Deployment", "Service", "PodDisruptionBudget"):
        if kind not in by_kind:
            fail(f"no {kind}")
    config = yaml.safe_load(by_kind["ConfigMap"][0]["data"]["scallopd.yaml"])
    deployment = by_kind["Deployment"][0]
    pod = deployment["spec"]["template"]["spec"]
    container = pod["containers"][0]
    ports = {p["name"]: p["containerPort"] for p in container["ports"]}
    if deployment["spec"]["replicas"] < 2:
        fail("fewer than 2 replicas: nothing to scale out")
    if ports["grpc"] != port_of(config["listen"]):
        fail("container port grpc differs from the config's listen port")
    if ports["metrics"] != port_of(config["metrics_listen"]):
        fail("container port metrics differs from the config's metrics_listen port")
    for probe in ("readinessProbe", "livenessProbe"):
        if container[probe]["grpc"]["port"] != ports["grpc"]:
            fail(f"{probe} does not check the gRPC health service on the grpc port")
    # Saturation turns the server's health NOT_SERVING: that must take the pod
    # out of the Service (readiness), not restart it (liveness).
    if container["readinessProbe"]["grpc"].get("service", "") != "":
        fail("readinessProbe must ask about the whole server (no service name)")
    if container["livenessProbe"]["grpc"].get("service") != "liveness":
        fail("livenessProbe must ask the 'liveness' service, which stays SERVING under load")
    uid = re.search(r"useradd .*--uid (\d+)", dockerfile)
    if not uid or pod["securityContext"]["runAsUser"] != int(uid.group(1)):
        fail("runAsUser differs from the Dockerfile's user")
    limit = mebibytes(container["resources"]["limits"]["memory"])
    if limit < config["cache_megabytes"] + 128:
        fail(f"memory limit {limit} Mi leaves under 128 Mi beside the cache budget")
    shutdown = config["drain_seconds"] + config["grace_seconds"] + config.get("hard_exit_seconds", 10)
    if pod["terminationGracePeriodSeconds"] < shutdown:
        fail("terminationGracePeriodSeconds is shorter than drain + grace + hard exit seconds")
    selector = deployment["spec"]["selector"]["matchLabels"]
    for service in by_kind["Service"]:
        if service["spec"]["selector"] != selector:
            fail(f"Service {service['metadata']['name']} does not select the Deployment's pods")
    headless = [s for s in by_kind["Service"] if s["spec"].get("clusterIP") == "None"]
    if not headless:
        fail("no headless Service: DNS would not list pods for client-side round_robin")
    return config


def check_config_starts(config, scallopd, cli):
    """The ConfigMap's configuration, on loopback ports, serves its worlds."""
    config = dict(config, listen="127.0.0.1:0", metrics_listen="127.0.0.1:0")
    with tempfile.TemporaryDirectory() as work:
        path = os.path.join(work, "scallopd.yaml")
        with open(path, "w") as out:
            yaml.safe_dump(config, out)
        server = subprocess.Popen([scallopd, "--config", path], stdout=subprocess.PIPE,
                                  stderr=subprocess.PIPE, text=True)
        try:
            line = server.stdout.readline().strip()
            if not line.startswith("scallopd listening on "):
                fail(f"the ConfigMap's config does not start scallopd: {server.stderr.read()}")
            address = line.rsplit(" ", 1)[1]
            info = None
            for _ in range(50):
                answer = subprocess.run([cli, "info", "--server", address, "--json"],
                                        capture_output=True, text=True)
                if answer.returncode == 0:
                    info = json.loads(answer.stdout)
                    break
                time.sleep(0.1)
            if info is None:
                fail("scallop info never answered")
            if sorted(info["worlds"]) != sorted(config["worlds"]):
                fail(f"server worlds {info['worlds']} differ from the ConfigMap's")
            if info["default_world"] != config["default_world"]:
                fail("default world differs")
        finally:
            server.kill()
            server.wait()


def main(manifest, dockerfile, scallopd, cli):
    with open(manifest) as f:
        documents = [d for d in yaml.safe_load_all(f) if d]
    with open(dockerfile) as f:
        config = check_structure(documents, f.read())
    check_config_starts(config, scallopd, cli)
    print(f"kubernetes manifests: {len(documents)} objects consistent; the config serves "
          f"{len(config['worlds'])} worlds")


if __name__ == "__main__":
    if len(sys.argv) != 5:
        fail(__doc__)
    main(*sys.argv[1:])
