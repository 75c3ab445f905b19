#!/usr/bin/python3
"""The web viewer (issue 21) in headless Chromium against a real scallopd:
opened from a link, panned by a mouse drag and zoomed by the wheel, it must
draw exactly the tiles' points in its view (fetched here as JSON tiles, a
decoder the page does not share), a radius-field world's too, and a layered
world's layer by layer (each drawn point's layer is its tile's, a hidden layer
is not drawn, the legend lists the layers in their colours), show a point's
id on hover, keep the view in the URL so the link reopens it, and leave a
screenshot that is not blank.

Usage: viewer_test.py SCALLOPD SCREENSHOT_PATH
"""
import json
import math
import random
import os
import subprocess
import sys
import tempfile
import time
import urllib.request

from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.action_chains import ActionChains
from selenium.webdriver.common.actions.wheel_input import ScrollOrigin
from selenium.webdriver.common.by import By

REGION_SIDE_IN_D = 16


def fail(message):
    print(f"viewer test: {message}", file=sys.stderr)
    sys.exit(1)


# A radius-field world (noise, R from 0.25 to 1): its tiles carry each point's R and are
# 6 r_max = 6 a side at level 0.
FIELD_CONFIG = """worlds:
  dunes: {seed: 4, radius_field: {noise: {r_min: 0.25, r_max: 1, frequency: 0.1, noise_seed: 9}}}
  forest: {seed: 7, layers: [{name: trees, min_distance: 4}, {name: bushes, min_distance: 1.5},
                             {name: rocks, min_distance: 0.75}]}
"""
# The layered world's smallest spacing: its tiles are 16 of it a side at level 0.
FOREST_D = 0.75
FIELD_R_MAX = 1.0


def start_scallopd(scallopd, log, config):
    server = subprocess.Popen(
        [scallopd, "--config", config, "--listen", "127.0.0.1:0", "--http-listen", "127.0.0.1:0",
         "--world", "coast:7:1:a3", "--world", "fine:9:0.25:a1:1.5", "--log-level", "warn"],
        stdout=subprocess.PIPE, stderr=log, text=True)
    for _ in range(4):
        line = server.stdout.readline()
        if line.startswith("scallopd http on "):
            return server, line.split()[-1]
    server.kill()
    fail("scallopd printed no http address")


def tiles_over(http, world, d, level, rect, region_side=None):
    """The JSON tiles overlapping rect (tiles of level 0 are regions: 16 d, or region_side for a
    radius-field world)."""
    side = (region_side or REGION_SIDE_IN_D * d) * 2 ** level
    for j in range(math.floor(rect[1] / side), math.floor(rect[3] / side) + 1):
        for i in range(math.floor(rect[0] / side), math.floor(rect[2] / side) + 1):
            url = f"http://{http}/v1/worlds/{world}/tiles/{i}/{j}.json?level={level}"
            with urllib.request.urlopen(url, timeout=20) as answer:
                yield json.load(answer)


def tile_points(http, world, d, level, rect, region_side=None):
    """The points of the JSON tiles overlapping rect that lie in it, by id."""
    points = {}
    for tile in tiles_over(http, world, d, level, rect, region_side):
        for k, identifier in enumerate(tile["ids"]):
            x, y = tile["xs"][k], tile["ys"][k]
            if rect[0] <= x < rect[2] and rect[1] <= y < rect[3]:
                points[identifier] = (x, y)
    return points


def layered_tile_points(http, world, d, level, rect):
    """A layered world's JSON tiles' points in rect, by (layer name, id)."""
    points = {}
    for tile in tiles_over(http, world, d, level, rect):
        for k, identifier in enumerate(tile["ids"]):
            x, y = tile["xs"][k], tile["ys"][k]
            if rect[0] <= x < rect[2] and rect[1] <= y < rect[3]:
                points[(tile["layer_names"][tile["layers"][k]], identifier)] = (x, y)
    return points


def check_layers(driver, http):
    """A layered world: every drawn point is its tile's, with the tile's layer, layer by layer;
    hiding a layer by its legend box removes exactly its points."""
    driver.execute_script("window.scallopViewer.setView({world: 'forest', x: 3.25, y: -7.5, z: 20,"
                          " draw: 'dots', background: 'none', hidden: []})")
    for hidden in ([], ["bushes"]):
        if hidden:
            box = driver.find_element(By.CSS_SELECTOR, "#layers input[data-layer='bushes']")
            box.click()
        state = wait_idle(driver, f"layered world, hidden {hidden}")
        names = [layer["name"] for layer in driver.execute_script("return window.scallopViewer.layers()")]
        if names != ["trees", "bushes", "rocks"]:
            fail(f"the legend lists {names}")
        drawn = {(names[p["layer"]], p["id"]): (p["x"], p["y"]) for p in
                 driver.execute_script("return window.scallopViewer.drawnPoints()")}
        expected = {key: value for key, value in
                    layered_tile_points(http, "forest", FOREST_D, state["level"], state["rect"]).items()
                    if key[0] not in hidden}
        for layer in ("trees", "bushes", "rocks"):
            mine = {key: value for key, value in drawn.items() if key[0] == layer}
            theirs = {key: value for key, value in expected.items() if key[0] == layer}
            if mine != theirs:
                fail(f"layer {layer} (hidden {hidden}): drawn {len(mine)} points, tiles {len(theirs)}")
            if layer not in hidden and len(theirs) < 5:
                fail(f"layer {layer}: only {len(theirs)} points in view, too few to judge")
        print(f"layered world, hidden {hidden}: {len(drawn)} points drawn = the tiles' points, "
              "layer by layer")
    if "hide=bushes" not in driver.current_url:
        time.sleep(0.3)
        if "hide=bushes" not in driver.current_url:
            fail(f"the URL does not hold the hidden layer: {driver.current_url}")


def wait_idle(driver, what, timeout=20):
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        state = driver.execute_script("return window.scallopViewer && window.scallopViewer.state()")
        if state and state["idle"] and state["rect"][2] > state["rect"][0]:
            # Two frames more: a render may be queued behind the last tile.
            time.sleep(0.05)
            again = driver.execute_script("return window.scallopViewer.state()")
            if again["idle"] and again == state:
                return state
        time.sleep(0.05)
    fail(f"{what}: the viewer never became idle")


def check_drawn(driver, http, d, what, region_side=None):
    """The points drawn in the view equal the tiles' points there, exactly."""
    state = wait_idle(driver, what)
    drawn = {p["id"]: (p["x"], p["y"]) for p in
             driver.execute_script("return window.scallopViewer.drawnPoints()")}
    expected = tile_points(http, state["world"], d, state["level"], state["rect"], region_side)
    if len(expected) < 50:
        fail(f"{what}: only {len(expected)} points in view, too few to judge")
    if drawn != expected:
        missing = sorted(set(expected) - set(drawn))[:5]
        extra = sorted(set(drawn) - set(expected))[:5]
        moved = [i for i in expected if i in drawn and drawn[i] != expected[i]][:5]
        fail(f"{what}: drawn {len(drawn)} points, tiles {len(expected)}; "
             f"missing {missing}, extra {extra}, moved {moved}")
    print(f"{what}: {len(drawn)} points drawn = the tiles' points "
          f"(level {state['level']}, rect {state['rect']})")
    return state


def check_background(driver, http, d, state, reach=None, region_side=None):
    """F1, F2 and the id against brute force; the points within 2 d (2 r_max with a radius
    field, `reach`) of the view hold both nearest points."""
    rect = state["rect"]
    margin = 2 * (reach or d)
    around = tile_points(http, state["world"], d, state["level"],
                         [rect[0] - margin, rect[1] - margin, rect[2] + margin, rect[3] + margin],
                         region_side)
    rng = random.Random(21)
    for _ in range(200):
        x = rng.uniform(rect[0], rect[2])
        y = rng.uniform(rect[1], rect[3])
        ranked = sorted(((px - x) * (px - x) + (py - y) * (py - y), int(i))
                        for i, (px, py) in around.items())
        page = driver.execute_script("return window.scallopViewer.nearest(arguments[0], arguments[1])", x, y)
        expected = (str(ranked[0][1]), math.sqrt(ranked[0][0]), math.sqrt(ranked[1][0]))
        if (page["id"], page["f1"], page["f2"]) != expected:
            fail(f"background at ({x!r}, {y!r}): page {page}, brute force {expected}")
    print("background: F1, F2 and cell id equal brute force at 200 places")


def main():
    scallopd, screenshot = sys.argv[1], sys.argv[2]
    log = tempfile.TemporaryFile(mode="w+")
    config = tempfile.NamedTemporaryFile(mode="w", suffix=".yaml", delete=False)
    config.write(FIELD_CONFIG)
    config.close()
    server, http = start_scallopd(scallopd, log, config.name)
    options = webdriver.ChromeOptions()
    options.binary_location = "/usr/bin/chromium"
    for argument in ["--headless=new", "--no-sandbox", "--disable-gpu",
                     "--disable-dev-shm-usage", "--window-size=1000,700",
                     "--force-device-scale-factor=1"]:
        options.add_argument(argument)
    driver = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)
    try:
        driver.set_script_timeout(20)
        driver.get(f"http://{http}/#world=coast&x=-3.5&y=7.25&z=30&draw=dots&bg=none&seams=1")
        state = check_drawn(driver, http, 1.0, "opened from a link")
        if (state["x"], state["y"], state["z"]) != (-3.5, 7.25, 30):
            fail(f"the link's view was not kept: {state}")

        # Pan: drag the canvas 240 px left and 90 px down; the plane follows.
        canvas = driver.find_element(By.ID, "plane")
        ActionChains(driver).move_to_element(canvas).click_and_hold() \
            .move_by_offset(-120, 45).move_by_offset(-120, 45).release().perform()
        panned = check_drawn(driver, http, 1.0, "after a drag")
        if not (math.isclose(panned["x"] - state["x"], 240 / 30, rel_tol=1e-9)
                and math.isclose(panned["y"] - state["y"], 90 / 30, rel_tol=1e-9)):
            fail(f"a drag of (-240, 90) px moved the view from {state} to {panned}")

        # Zoom out with the wheel until the tiles change level.
        for _ in range(6):
            ActionChains(driver).scroll_from_origin(ScrollOrigin.from_element(canvas), 0, 300).perform()
            time.sleep(0.05)
        zoomed = check_drawn(driver, http, 1.0, "after zooming out with the wheel")
        if not (zoomed["z"] < panned["z"] / 4 and zoomed["level"] >= 1):
            fail(f"the wheel did not zoom out to a coarser level: {zoomed}")

        # Another world by the page's own control, with disks, the noise background on.
        driver.execute_script("window.scallopViewer.setView({world: 'fine', x: 100.125, y: -50, z: 40,"
                              " draw: 'disks', background: 'cell'})")
        fine = check_drawn(driver, http, 0.25, "world 'fine' with disks and cells")
        if fine["world"] != "fine":
            fail(f"the world did not change: {fine}")

        # The background's F1, F2 and cell id at random places in view, against
        # a brute-force search of the JSON tiles' points around the view.
        check_background(driver, http, 0.25, fine)

        # Hover over a drawn point: its id and exact coordinates appear.
        points = driver.execute_script("return window.scallopViewer.drawnPoints()")
        point = min(points, key=lambda p: math.hypot(p["x"] - fine["x"], p["y"] - fine["y"]))
        scale = fine["z"] / 0.25
        px = (point["x"] - fine["rect"][0]) * scale
        py = (fine["rect"][3] - point["y"]) * scale
        size = canvas.size
        ActionChains(driver).move_to_element_with_offset(
            canvas, px - size["width"] / 2, py - size["height"] / 2).perform()
        time.sleep(0.1)
        hover = driver.find_element(By.ID, "hover")
        if not hover.is_displayed() or point["id"] not in hover.text or repr(point["x"]) not in hover.text:
            fail(f"hovering {point} shows {hover.text!r}")

        # The URL holds the view: reopening it gives the same view and points.
        time.sleep(0.3)  # the fragment is written 150 ms after the last change
        link = driver.current_url
        drawn_before = driver.execute_script("return window.scallopViewer.drawnPoints()")
        driver.get("about:blank")
        driver.get(link)
        reopened = check_drawn(driver, http, 0.25, "reopened from its own URL")
        for field in ("world", "x", "y", "z", "level", "rect"):
            if reopened[field] != fine[field]:
                fail(f"the URL {link} reopened {field} {reopened[field]}, not {fine[field]}")
        if driver.execute_script("return window.scallopViewer.drawnPoints()") != drawn_before:
            fail("the reopened view draws other points")

        # Not blank: the canvas has ground, disks and cell colours.
        colours = driver.execute_script("""
            const canvas = document.getElementById('plane');
            const pixels = canvas.getContext('2d').getImageData(0, 0, canvas.width, canvas.height).data;
            const seen = new Set();
            for (let k = 0; k < pixels.length; k += 4 * 97) seen.add(pixels[k] << 16 | pixels[k + 1] << 8 | pixels[k + 2]);
            return seen.size;""")
        driver.save_screenshot(screenshot)
        if colours < 50 or os.path.getsize(screenshot) < 20000:
            fail(f"the picture looks blank: {colours} colours, {os.path.getsize(screenshot)} bytes")
        errors = [entry for entry in driver.get_log("browser") if entry["level"] == "SEVERE"]
        if errors:
            fail(f"the page logged errors: {errors}")
        print(f"screenshot {screenshot}: {colours} colours sampled")

        # A radius-field world: its tiles' points drawn as disks of their own R, and the
        # background's nearest points found as far as F2 < 2 r_max reaches.
        driver.execute_script("window.scallopViewer.setView({world: 'dunes', x: 10.5, y: -4, z: 15,"
                              " draw: 'disks', background: 'f2-f1'})")
        dunes = check_drawn(driver, http, 0.25, "radius-field world 'dunes' with disks",
                            6 * FIELD_R_MAX)
        check_background(driver, http, 0.25, dunes, FIELD_R_MAX, 6 * FIELD_R_MAX)
        errors = [entry for entry in driver.get_log("browser") if entry["level"] == "SEVERE"]
        if errors:
            fail(f"the page logged errors on the field world: {errors}")
        check_layers(driver, http)
        errors = [entry for entry in driver.get_log("browser") if entry["level"] == "SEVERE"]
        if errors:
            fail(f"the page logged errors on the layered world: {errors}")
    finally:
        driver.quit()
        server.terminate()
        server.wait(timeout=20)
        os.unlink(config.name)
    print("viewer test: passed")


if __name__ == "__main__":
    main()
