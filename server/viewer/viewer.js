// Scallop's web viewer: pans and zooms a world's infinite plane, drawn from
// the binary tiles of GET /v1/worlds/{world}/tiles/{i}/{j}.bin (the format is
// in docs/tiles.md). Plain JavaScript, no build step; scallopd embeds it.
//
// The view is (world, centre x, y, zoom z in pixels per d), kept in the URL's
// fragment so a link reopens the same place. A layered world's points are
// drawn in their layer's colour (the world list gives each layer's), with a
// legend whose boxes show and hide layers (`hide=` in the fragment). The noise background (F1,
// F2 - F1, cell id) is computed here from the tiles' points: every point
// within 2 d of the screen is loaded, which is enough because F2 < 2 d on a
// maximal Poisson-disk set (docs/noise.md).
'use strict';

(() => {
  const REGION_SIDE_IN_D = 16;
  // The level is the smallest whose tiles are at least this wide on screen.
  const TILE_SCREEN_PIXELS = 256;
  // Zooming out stops at this much plane on screen: about 35,000 A3 points.
  const MAX_VIEW_AREA_IN_D2 = 40000;
  const MAX_ZOOM = 400;  // pixels per d
  const MAX_TILES_KEPT = 600;
  const MAX_FETCHES = 6;
  const PRECISION_LIMIT_IN_D = 2 ** 32;

  const canvas = document.getElementById('plane');
  const context = canvas.getContext('2d');
  const controls = {
    world: document.getElementById('world'),
    draw: document.getElementById('draw'),
    background: document.getElementById('background'),
    seams: document.getElementById('seams'),
    tokenField: document.getElementById('token-field'),
    token: document.getElementById('token'),
    status: document.getElementById('status'),
    hover: document.getElementById('hover'),
    layers: document.getElementById('layers'),
  };

  // hidden: names of a layered world's layers not drawn.
  const view = { world: '', x: 0, y: 0, z: 24, draw: 'dots', background: 'none', seams: false, hidden: [] };
  let worlds = new Map();  // name -> the world list's entry
  let maxLevel = 0;
  let token = sessionStorage.getItem('scallop-token') || '';

  // ---- The URL ---------------------------------------------------------

  function readFragment() {
    const fields = new URLSearchParams(location.hash.slice(1));
    const number = (name, fallback) => {
      const value = Number(fields.get(name));
      return fields.has(name) && Number.isFinite(value) ? value : fallback;
    };
    view.world = fields.get('world') || view.world;
    view.x = number('x', view.x);
    view.y = number('y', view.y);
    view.z = number('z', view.z);
    if (['dots', 'disks'].includes(fields.get('draw'))) view.draw = fields.get('draw');
    if (['none', 'f1', 'f2-f1', 'cell'].includes(fields.get('bg'))) view.background = fields.get('bg');
    if (fields.has('seams')) view.seams = fields.get('seams') === '1';
    if (fields.has('hide')) view.hidden = fields.get('hide').split(',').filter((name) => name);
  }

  let fragmentTimer = 0;
  function writeFragment() {
    clearTimeout(fragmentTimer);
    fragmentTimer = setTimeout(() => {
      const fields = new URLSearchParams({
        world: view.world, x: String(view.x), y: String(view.y), z: String(view.z),
        draw: view.draw, bg: view.background, seams: view.seams ? '1' : '0',
      });
      if (view.hidden.length) fields.set('hide', view.hidden.join(','));
      history.replaceState(null, '', '#' + fields.toString());
    }, 150);
  }

  // ---- Geometry --------------------------------------------------------

  function minDistance() {
    const world = worlds.get(view.world);
    return world ? world.min_distance : 1;
  }
  // The largest spacing: d, or r_max in a radius-field world, which bounds
  // F1 and F2 / 2 (docs/noise.md).
  function largestSpacing() {
    const world = worlds.get(view.world);
    return world ? world.r_max || world.min_distance : 1;
  }
  function cssSize() {
    return { width: canvas.clientWidth || window.innerWidth, height: canvas.clientHeight || window.innerHeight };
  }
  function minZoom() {
    const { width, height } = cssSize();
    return Math.sqrt((width * height) / MAX_VIEW_AREA_IN_D2);
  }
  function clampView() {
    view.z = Math.min(MAX_ZOOM, Math.max(minZoom(), view.z));
    const limit = PRECISION_LIMIT_IN_D * minDistance() * 0.999;
    view.x = Math.min(limit, Math.max(-limit, view.x));
    view.y = Math.min(limit, Math.max(-limit, view.y));
  }
  // Pixels per world unit.
  function scale() { return view.z / minDistance(); }
  // The half-open world rectangle on screen: [x0, x1) x [y0, y1), y up.
  function viewRect() {
    const { width, height } = cssSize();
    const s = scale();
    return [view.x - width / 2 / s, view.y - height / 2 / s, view.x + width / 2 / s, view.y + height / 2 / s];
  }
  function toScreen(x, y) {
    const { width, height } = cssSize();
    const s = scale();
    return [(x - view.x) * s + width / 2, height / 2 - (y - view.y) * s];
  }
  function toWorld(px, py) {
    const { width, height } = cssSize();
    const s = scale();
    return [view.x + (px - width / 2) / s, view.y - (py - height / 2) / s];
  }
  // A level-0 tile is one region: 16 d, or a radius-field world's 6 r_max.
  function regionSide() {
    const world = worlds.get(view.world);
    return world && world.region_side ? world.region_side : REGION_SIDE_IN_D * minDistance();
  }
  function level() {
    const tileSideInPixels = regionSide() * scale();  // a level-0 tile
    const wanted = Math.ceil(Math.log2(TILE_SCREEN_PIXELS / tileSideInPixels));
    return Math.min(maxLevel, Math.max(0, wanted));
  }

  // ---- Tiles -----------------------------------------------------------

  const tiles = new Map();  // key -> {status, points, error, used}
  const queue = [];
  let fetching = 0;

  function tileKey(world, L, i, j) { return `${world}/${L}/${i}/${j}`; }

  // The tiles covering the view grown by `margin` (world units).
  function tilesAround(margin) {
    const L = level();
    const side = regionSide() * 2 ** L;
    const [x0, y0, x1, y1] = viewRect();
    // Tiles -half .. half - 1 cover the precision range (2^28 regions of 16 d a side).
    const world = worlds.get(view.world);
    const half = world && world.precision_limit ? Math.ceil(world.precision_limit / side) : 2 ** (28 - L);
    const index = (v) => Math.min(half - 1, Math.max(-half, Math.floor(v / side)));
    const wanted = [];
    for (let j = index(y0 - margin); j <= index(y1 + margin); ++j) {
      for (let i = index(x0 - margin); i <= index(x1 + margin); ++i) wanted.push({ L, i, j, side });
    }
    return wanted;
  }

  // docs/tiles.md, "Binary": an 80-byte little-endian header, then ids, xs, ys.
  function parseTile(buffer) {
    const data = new DataView(buffer);
    const magic = String.fromCharCode(...new Uint8Array(buffer, 0, 4));
    if (magic !== 'SCTL' || data.getUint16(4, true) !== 1) throw new Error('not a version 1 tile');
    if (data.getUint16(6, true) & ~0x3) throw new Error('tile has arrays this viewer does not know');
    const n = data.getUint32(8, true);
    const points = {
      n,
      idLow: new Uint32Array(n), idHigh: new Uint32Array(n),
      xs: new Float64Array(n), ys: new Float64Array(n),
      rs: null,  // radius fields (coming): one radius a point
      layers: null,  // layers (coming): one small integer a point
    };
    for (let k = 0; k < n; ++k) {
      points.idLow[k] = data.getUint32(80 + 8 * k, true);
      points.idHigh[k] = data.getUint32(84 + 8 * k, true);
      points.xs[k] = data.getFloat64(80 + 8 * n + 8 * k, true);
      points.ys[k] = data.getFloat64(80 + 16 * n + 8 * k, true);
    }
    let offset = 80 + 24 * n;
    if (data.getUint16(6, true) & 1) {
      points.rs = new Float64Array(n);
      for (let k = 0; k < n; ++k) points.rs[k] = data.getFloat64(offset + 8 * k, true);
      offset += 8 * n;
    }
    if (data.getUint16(6, true) & 2) {
      points.layers = new Uint16Array(n);
      for (let k = 0; k < n; ++k) points.layers[k] = data.getUint16(offset + 2 * k, true);
    }
    return points;
  }

  function idText(points, k) {
    return ((BigInt(points.idHigh[k]) << 32n) | BigInt(points.idLow[k])).toString();
  }

  // ---- Layers ----------------------------------------------------------

  // The world's layers from the world list ([{name, colour, r_min, r_max}]), or [].
  function layersOf() {
    const world = worlds.get(view.world);
    return (world && world.layers) || [];
  }
  // Per layer number: shown or not, and its colour as a little-endian RGBA word (ImageData).
  function layerStyles() {
    return layersOf().map((layer) => {
      const rgb = parseInt(layer.colour.slice(1), 16);
      return {
        shown: !view.hidden.includes(layer.name),
        colour: layer.colour,
        word: (0xff000000 | ((rgb & 0xff) << 16) | (rgb & 0xff00) | (rgb >> 16)) >>> 0,
      };
    });
  }
  // The legend: one box a layer, in its colour; unticking one hides its points.
  let legendWorld = null;
  function syncLegend() {
    const layers = layersOf();
    controls.layers.hidden = layers.length === 0;
    if (legendWorld !== view.world) {
      legendWorld = view.world;
      controls.layers.replaceChildren(...layers.map((layer) => {
        const label = document.createElement('label');
        const box = document.createElement('input');
        box.type = 'checkbox';
        box.dataset.layer = layer.name;
        box.addEventListener('change', () => {
          view.hidden = view.hidden.filter((name) => name !== layer.name);
          if (!box.checked) view.hidden.push(layer.name);
          requestRender();
        });
        const swatch = document.createElement('span');
        swatch.className = 'swatch';
        swatch.style.background = layer.colour;
        label.append(box, swatch, ' ' + layer.name);
        return label;
      }));
    }
    for (const box of controls.layers.querySelectorAll('input')) {
      box.checked = !view.hidden.includes(box.dataset.layer);
    }
  }

  function headers() { return token ? { Authorization: 'Bearer ' + token } : {}; }

  async function errorText(response) {
    try {
      const body = await response.json();
      return `${response.status} ${body.error.status}: ${body.error.message}`;
    } catch (e) {
      return `${response.status} ${response.statusText}`;
    }
  }

  function pump() {
    while (fetching < MAX_FETCHES && queue.length > 0) {
      const { key, url } = queue.shift();
      const entry = tiles.get(key);
      if (!entry || entry.status !== 'queued') continue;
      entry.status = 'loading';
      ++fetching;
      fetch(url, { headers: headers() })
        .then(async (response) => {
          if (!response.ok) throw new Error(await errorText(response));
          entry.points = parseTile(await response.arrayBuffer());
          entry.status = 'ready';
        })
        .catch((error) => {
          entry.status = 'error';
          entry.error = String(error.message || error);
          if (entry.error.startsWith('401')) askForToken();
        })
        .finally(() => {
          --fetching;
          pump();
          requestRender();
        });
    }
  }

  // Queues the tiles the view needs (nearest the centre first) and returns
  // the ones it wants, loaded or not.
  function requestTiles(margin) {
    const wanted = tilesAround(margin);
    const now = performance.now();
    const fresh = [];
    for (const tile of wanted) {
      const key = tileKey(view.world, tile.L, tile.i, tile.j);
      tile.key = key;
      let entry = tiles.get(key);
      if (!entry) {
        entry = { status: 'queued' };
        tiles.set(key, entry);
        const centre = [(tile.i + 0.5) * tile.side, (tile.j + 0.5) * tile.side];
        fresh.push({
          key,
          distance: Math.hypot(centre[0] - view.x, centre[1] - view.y),
          url: `/v1/worlds/${encodeURIComponent(view.world)}/tiles/${tile.i}/${tile.j}.bin?level=${tile.L}`,
        });
      }
      entry.used = now;
      tile.entry = entry;
    }
    fresh.sort((a, b) => a.distance - b.distance);
    queue.push(...fresh);
    // Tiles no longer wanted leave the queue; the least recently used go.
    const wantedKeys = new Set(wanted.map((tile) => tile.key));
    for (let k = queue.length - 1; k >= 0; --k) {
      if (!wantedKeys.has(queue[k].key)) {
        tiles.delete(queue[k].key);
        queue.splice(k, 1);
      }
    }
    if (tiles.size > MAX_TILES_KEPT) {
      const old = [...tiles.entries()].filter(([key, entry]) => !wantedKeys.has(key) && entry.status !== 'loading');
      old.sort((a, b) => a[1].used - b[1].used);
      for (const [key] of old.slice(0, tiles.size - MAX_TILES_KEPT)) tiles.delete(key);
    }
    pump();
    return wanted;
  }

  // ---- The loaded points, gridded by d ---------------------------------

  // Every point of the ready tiles in typed arrays, with a grid of cells of
  // side d over their tiles: cell c holds points cellPoints[cellStart[c] ..
  // cellStart[c + 1]). Rebuilt only when the set of ready tiles changes, so
  // panning over loaded tiles rebuilds nothing.
  let grid = null;
  let gridKey = '';
  function buildGrid(ready) {
    const d = minDistance();
    let n = 0, x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
    for (const tile of ready) {
      n += tile.entry.points.n;
      x0 = Math.min(x0, tile.i * tile.side);
      y0 = Math.min(y0, tile.j * tile.side);
      x1 = Math.max(x1, (tile.i + 1) * tile.side);
      y1 = Math.max(y1, (tile.j + 1) * tile.side);
    }
    const xs = new Float64Array(n), ys = new Float64Array(n);
    const tileOf = new Uint16Array(n), index = new Uint32Array(n);
    const owners = ready.map((tile) => tile.entry.points);
    let k = 0;
    owners.forEach((points, t) => {
      xs.set(points.xs, k);
      ys.set(points.ys, k);
      for (let m = 0; m < points.n; ++m, ++k) { tileOf[k] = t; index[k] = m; }
    });
    const gx0 = n ? Math.floor(x0 / d) : 0, gy0 = n ? Math.floor(y0 / d) : 0;
    const columns = n ? Math.floor(x1 / d) - gx0 + 1 : 1, rows = n ? Math.floor(y1 / d) - gy0 + 1 : 1;
    const cellOf = new Int32Array(n);
    const cellStart = new Int32Array(columns * rows + 1);
    for (let m = 0; m < n; ++m) {
      const cx = Math.min(columns - 1, Math.max(0, Math.floor(xs[m] / d) - gx0));
      const cy = Math.min(rows - 1, Math.max(0, Math.floor(ys[m] / d) - gy0));
      cellOf[m] = cy * columns + cx;
      ++cellStart[cellOf[m] + 1];
    }
    for (let c = 0; c < columns * rows; ++c) cellStart[c + 1] += cellStart[c];
    const fill = cellStart.slice(0, columns * rows);
    const cellPoints = new Int32Array(n);
    for (let m = 0; m < n; ++m) cellPoints[fill[cellOf[m]]++] = m;
    const reach = largestSpacing();
    return { d, reach, n, gx0, gy0, columns, rows, cellStart, cellPoints, xs, ys, owners, tileOf, index };
  }

  // The nearest and second nearest points to (x, y), into these (indices
  // into the grid, distances; -1 and Infinity if none), by squared
  // distances in doubles as the server ranks them (ties aside). The 3 x 3
  // cells around (x, y) first; the ring around them only when the second
  // point found is farther than the nearest edge of those 9 cells (at least
  // d away), then further rings until it is not. F2 < 2 d, so the 5 x 5
  // cells suffice on a constant world; a radius-field world's grid has cells
  // of r_min and F2 < 2 r_max, so up to 2 r_max / r_min + 1 rings.
  let nearFirst = -1, nearSecond = -1, nearF1 = Infinity, nearF2 = Infinity;
  let best = Infinity, next = Infinity;
  function scanCell(i, j, x, y) {
    const g = grid;
    if (i < 0 || j < 0 || i >= g.columns || j >= g.rows) return;
    const c = j * g.columns + i;
    for (let s = g.cellStart[c], end = g.cellStart[c + 1]; s < end; ++s) {
      const k = g.cellPoints[s];
      const dx = g.xs[k] - x, dy = g.ys[k] - y;
      const squared = dx * dx + dy * dy;
      if (squared < best) { nearSecond = nearFirst; next = best; nearFirst = k; best = squared; }
      else if (squared < next) { nearSecond = k; next = squared; }
    }
  }
  function nearestTwo(x, y) {
    const g = grid;
    const fx = x / g.d, fy = y / g.d;
    const cx = Math.floor(fx) - g.gx0, cy = Math.floor(fy) - g.gy0;
    nearFirst = -1; nearSecond = -1; best = Infinity; next = Infinity;
    for (let j = cy - 1; j <= cy + 1; ++j) for (let i = cx - 1; i <= cx + 1; ++i) scanCell(i, j, x, y);
    const edge = Math.min(fx - Math.floor(fx), Math.ceil(fx) - fx, fy - Math.floor(fy), Math.ceil(fy) - fy);
    const rings = Math.ceil(2 * g.reach / g.d) + 1;
    for (let ring = 2; ring <= rings; ++ring) {
      const inner = g.d * (ring - 1 + edge);
      if (next <= inner * inner) break;
      for (let i = cx - ring; i <= cx + ring; ++i) { scanCell(i, cy - ring, x, y); scanCell(i, cy + ring, x, y); }
      for (let j = cy - ring + 1; j <= cy + ring - 1; ++j) { scanCell(cx - ring, j, x, y); scanCell(cx + ring, j, x, y); }
    }
    nearF1 = Math.sqrt(best); nearF2 = Math.sqrt(next);
  }

  function pointId(k) { return idText(grid.owners[grid.tileOf[k]], grid.index[k]); }
  // The layer of grid point k (its number in the world's order), or -1 without layers.
  function layerOf(k) {
    const points = grid.owners[grid.tileOf[k]];
    return points.layers ? points.layers[grid.index[k]] : -1;
  }

  // A colour (0xAABBGGRR, for a little-endian Uint32Array view of RGBA
  // bytes) a cell keeps wherever it is seen: a hash of its point's id.
  function cellColour(k) {
    const points = grid.owners[grid.tileOf[k]], m = grid.index[k];
    let h = (points.idLow[m] ^ Math.imul(points.idHigh[m], 0x9e3779b1)) >>> 0;
    h = Math.imul(h ^ (h >>> 16), 0x85ebca6b) >>> 0;
    h = Math.imul(h ^ (h >>> 13), 0xc2b2ae35) >>> 0;
    h ^= h >>> 16;
    return (0xff000000 | ((128 + ((h >>> 16) & 0x7f)) << 16) | ((128 + ((h >>> 8) & 0x7f)) << 8) | (128 + (h & 0x7f))) >>> 0;
  }
  function grey(value) {
    const level = Math.round(255 * Math.min(1, Math.max(0, value)));
    return (0xff000000 | (level << 16) | (level << 8) | level) >>> 0;
  }

  // ---- Drawing -----------------------------------------------------------

  // Dots are written as pixels into a layer of their own, drawn over the
  // background; disks and seams are drawn over both as paths. (A canvas path
  // of 30,000 arcs takes hundreds of milliseconds, 30,000 dots written as
  // pixels a few.)
  const dotsCanvas = document.createElement('canvas');
  let frame = null;
  let frameWords = null;
  let drawn = { rect: [0, 0, 0, 0], shown: [], idle: false, level: 0 };
  let renderPending = false;
  let renderMilliseconds = 0;

  function requestRender() {
    if (renderPending) return;
    renderPending = true;
    requestAnimationFrame(render);
  }

  // Fills device pixels [x0, x1) x [y0, y1) of the frame with `colour`.
  function fillPixels(x0, y0, x1, y1, colour) {
    const width = frame.width;
    x0 = Math.max(0, x0); y0 = Math.max(0, y0);
    x1 = Math.min(width, x1); y1 = Math.min(frame.height, y1);
    for (let y = y0; y < y1; ++y) frameWords.fill(colour, y * width + x0, y * width + x1);
  }

  // The background channel, one sample a block of about 20,000 blocks on
  // screen (at least 4 CSS pixels), drawn scaled up (smoothly for F1 and
  // F2 - F1, in flat cells for the cell id).
  const noiseCanvas = document.createElement('canvas');
  function drawBackground(width, height) {
    const block = Math.max(4, Math.ceil(Math.sqrt((width * height) / 20000)));
    const columns = Math.ceil(width / block), rows = Math.ceil(height / block);
    if (noiseCanvas.width !== columns || noiseCanvas.height !== rows) {
      noiseCanvas.width = columns;
      noiseCanvas.height = rows;
    }
    const noiseContext = noiseCanvas.getContext('2d');
    const image = noiseContext.createImageData(columns, rows);
    const words = new Uint32Array(image.data.buffer);
    const s = scale();
    for (let r = 0; r < rows; ++r) {
      const y = view.y - ((r + 0.5) * block - height / 2) / s;
      for (let c = 0; c < columns; ++c) {
        nearestTwo(view.x + ((c + 0.5) * block - width / 2) / s, y);
        let colour = 0xffffffff;
        if (nearFirst >= 0) {
          if (view.background === 'cell') colour = cellColour(nearFirst);
          else colour = grey(view.background === 'f1' ? nearF1 / grid.reach : (nearF2 - nearF1) / grid.reach);
        }
        words[r * columns + c] = colour;
      }
    }
    noiseContext.putImageData(image, 0, 0);
    context.imageSmoothingEnabled = view.background !== 'cell';
    context.drawImage(noiseCanvas, 0, 0, columns * block, rows * block);
  }

  function drawSeams(width, height) {
    const side = regionSide();
    if (side * scale() < 6) return;  // too dense to mean anything
    const [x0, y0, x1, y1] = viewRect();
    context.beginPath();
    for (let i = Math.ceil(x0 / side); i * side < x1; ++i) {
      const [px] = toScreen(i * side, 0);
      context.moveTo(Math.round(px) + 0.5, 0);
      context.lineTo(Math.round(px) + 0.5, height);
    }
    for (let j = Math.ceil(y0 / side); j * side < y1; ++j) {
      const [, py] = toScreen(0, j * side);
      context.moveTo(0, Math.round(py) + 0.5);
      context.lineTo(width, Math.round(py) + 0.5);
    }
    context.strokeStyle = 'rgba(220, 40, 40, 0.7)';
    context.lineWidth = 1;
    context.stroke();
  }

  function render() {
    const start = performance.now();
    renderPending = false;
    const ratio = window.devicePixelRatio || 1;
    const { width, height } = cssSize();
    if (canvas.width !== Math.round(width * ratio) || canvas.height !== Math.round(height * ratio)) {
      canvas.width = Math.round(width * ratio);
      canvas.height = Math.round(height * ratio);
    }
    if (!frame || frame.width !== canvas.width || frame.height !== canvas.height) {
      frame = context.createImageData(canvas.width, canvas.height);
      frameWords = new Uint32Array(frame.data.buffer);
      dotsCanvas.width = canvas.width;
      dotsCanvas.height = canvas.height;
    }
    frameWords.fill(0);  // transparent
    context.setTransform(ratio, 0, 0, ratio, 0, 0);
    context.fillStyle = '#fff';
    context.fillRect(0, 0, width, height);
    if (!worlds.has(view.world)) return;
    clampView();

    const d = minDistance();
    const margin = 2 * largestSpacing();  // F2 < 2 d (2 r_max): what the background needs around the screen
    const wanted = requestTiles(margin);
    const ready = wanted.filter((tile) => tile.entry.status === 'ready');
    const key = view.world + ':' + ready.map((tile) => tile.key).join('|');
    if (key !== gridKey) {
      grid = buildGrid(ready);
      gridKey = key;
    }
    if (view.background !== 'none') drawBackground(width, height);

    // Points whose centres are on screen; dots written straight into the frame.
    const rect = viewRect();
    const s = scale();
    const disks = view.draw === 'disks' && (d / 2) * s * ratio >= 2.5;
    const dot = Math.max(2, Math.min(6, Math.round(0.24 * d * s))) * ratio;
    const shown = [];
    const dark = 0xff1b1b1b;
    const styles = layerStyles();
    for (let k = 0; k < grid.n; ++k) {
      const x = grid.xs[k], y = grid.ys[k];
      if (x < rect[0] || x >= rect[2] || y < rect[1] || y >= rect[3]) continue;
      const layer = layerOf(k);
      if (layer >= 0 && !(styles[layer] && styles[layer].shown)) continue;
      shown.push(k);
      if (!disks) {
        const px = Math.round(((x - view.x) * s + width / 2) * ratio - dot / 2);
        const py = Math.round((height / 2 - (y - view.y) * s) * ratio - dot / 2);
        fillPixels(px, py, px + dot, py + dot, layer >= 0 ? styles[layer].word : dark);
      }
    }
    if (!disks) {
      dotsCanvas.getContext('2d').putImageData(frame, 0, 0);
      context.setTransform(1, 0, 0, 1, 0, 0);
      context.drawImage(dotsCanvas, 0, 0);
      context.setTransform(ratio, 0, 0, ratio, 0, 0);
    }
    if (disks) {
      // Disks reach beyond the screen's edge: points just off it are drawn too.
      const radius = (d / 2) * s;
      // One path a layer (a world without layers: one), each filled in its colour.
      const paths = styles.length ? styles.map(() => new Path2D()) : [new Path2D()];
      for (let k = 0; k < grid.n; ++k) {
        const points = grid.owners[grid.tileOf[k]];
        const layer = layerOf(k);
        if (layer >= 0 && !(styles[layer] && styles[layer].shown)) continue;
        // A radius field's point (or a layer's) is drawn at its own radius, when tiles carry one.
        const r = points.rs ? (points.rs[grid.index[k]] / 2) * s : radius;
        const px = (grid.xs[k] - view.x) * s + width / 2, py = height / 2 - (grid.ys[k] - view.y) * s;
        if (px < -r || px > width + r || py < -r || py > height + r) continue;
        const path = paths[Math.max(0, layer)];
        path.moveTo(px + r, py);
        path.arc(px, py, r, 0, 2 * Math.PI);
      }
      paths.forEach((path, layer) => {
        context.globalAlpha = styles.length ? 0.45 : 1;
        context.fillStyle = styles.length ? styles[layer].colour : 'rgba(40, 90, 170, 0.35)';
        context.fill(path);
        context.globalAlpha = 1;
        context.strokeStyle = styles.length ? styles[layer].colour : 'rgba(20, 50, 110, 0.9)';
        context.lineWidth = 1;
        context.stroke(path);
      });
    }
    if (view.seams) drawSeams(width, height);

    const pending = wanted.filter((tile) => tile.entry.status === 'queued' || tile.entry.status === 'loading');
    const failed = wanted.find((tile) => tile.entry.status === 'error');
    drawn = { rect, shown, idle: pending.length === 0, level: level() };
    renderMilliseconds = performance.now() - start;
    controls.status.classList.toggle('error', Boolean(failed));
    controls.status.textContent = failed
      ? failed.entry.error
      : `${shown.length.toLocaleString()} points · level ${level()} · ${pending.length ? pending.length + ' tiles loading' : 'x ' + view.x.toPrecision(8) + ', y ' + view.y.toPrecision(8)}`;
    writeFragment();
  }

  // ---- Interaction -------------------------------------------------------

  function panBy(dx, dy) {
    const s = scale();
    view.x -= dx / s;
    view.y += dy / s;
    requestRender();
  }
  function zoomAt(factor, px, py) {
    const [wx, wy] = toWorld(px, py);
    view.z *= factor;
    clampView();
    // Keep the world point under the cursor where it was.
    const [nx, ny] = toWorld(px, py);
    view.x += wx - nx;
    view.y += wy - ny;
    requestRender();
  }

  let drag = null;
  canvas.addEventListener('pointerdown', (event) => {
    drag = { x: event.clientX, y: event.clientY };
    canvas.setPointerCapture(event.pointerId);
    canvas.classList.add('dragging');
    controls.hover.hidden = true;
  });
  canvas.addEventListener('pointermove', (event) => {
    if (drag) {
      panBy(event.clientX - drag.x, event.clientY - drag.y);
      drag = { x: event.clientX, y: event.clientY };
    } else {
      showHover(event.clientX, event.clientY);
    }
  });
  const endDrag = () => { drag = null; canvas.classList.remove('dragging'); };
  canvas.addEventListener('pointerup', endDrag);
  canvas.addEventListener('pointercancel', endDrag);
  canvas.addEventListener('pointerleave', () => { controls.hover.hidden = true; });
  canvas.addEventListener('wheel', (event) => {
    event.preventDefault();
    const pixels = event.deltaMode === 1 ? event.deltaY * 16 : event.deltaY;
    zoomAt(Math.exp(-pixels * 0.002), event.clientX, event.clientY);
  }, { passive: false });
  window.addEventListener('keydown', (event) => {
    if (event.target instanceof HTMLInputElement || event.target instanceof HTMLSelectElement) return;
    const { width, height } = cssSize();
    const step = 80;
    const keys = {
      ArrowLeft: () => panBy(step, 0), ArrowRight: () => panBy(-step, 0),
      ArrowUp: () => panBy(0, step), ArrowDown: () => panBy(0, -step),
      '+': () => zoomAt(1.25, width / 2, height / 2), '=': () => zoomAt(1.25, width / 2, height / 2),
      '-': () => zoomAt(0.8, width / 2, height / 2),
    };
    if (keys[event.key]) { keys[event.key](); event.preventDefault(); }
  });
  document.getElementById('zoom-in').addEventListener('click', () => {
    const { width, height } = cssSize();
    zoomAt(1.5, width / 2, height / 2);
  });
  document.getElementById('zoom-out').addEventListener('click', () => {
    const { width, height } = cssSize();
    zoomAt(1 / 1.5, width / 2, height / 2);
  });
  window.addEventListener('resize', requestRender);
  window.addEventListener('hashchange', () => { readFragment(); syncControls(); requestRender(); });

  function showHover(px, py) {
    if (!grid || grid.n === 0) return;
    const [x, y] = toWorld(px, py);
    nearestTwo(x, y);
    const s = scale();
    const reach = Math.max(8, view.draw === 'disks' ? (minDistance() / 2) * s : 8);
    if (nearFirst < 0 || nearF1 * s > reach) {
      controls.hover.hidden = true;
      return;
    }
    const k = nearFirst;
    const layer = layerOf(k);
    const name = layer >= 0 && layersOf()[layer] ? `\nlayer ${layersOf()[layer].name}` : '';
    controls.hover.textContent = `id ${pointId(k)}${name}\nx  ${String(grid.xs[k])}\ny  ${String(grid.ys[k])}`;
    controls.hover.style.left = `${px + 14}px`;
    controls.hover.style.top = `${py + 14}px`;
    controls.hover.hidden = false;
  }

  function syncControls() {
    controls.world.value = view.world;
    controls.draw.value = view.draw;
    controls.background.value = view.background;
    controls.seams.checked = view.seams;
    syncLegend();
  }
  controls.world.addEventListener('change', () => {
    view.world = controls.world.value;
    view.hidden = [];
    syncLegend();
    requestRender();
  });
  controls.draw.addEventListener('change', () => { view.draw = controls.draw.value; requestRender(); });
  controls.background.addEventListener('change', () => { view.background = controls.background.value; requestRender(); });
  controls.seams.addEventListener('change', () => { view.seams = controls.seams.checked; requestRender(); });

  // ---- Worlds and the token -----------------------------------------------

  function askForToken() {
    controls.tokenField.hidden = false;
    controls.token.focus();
  }
  controls.token.addEventListener('change', () => {
    token = controls.token.value.trim();
    sessionStorage.setItem('scallop-token', token);
    tiles.clear();
    queue.length = 0;
    gridKey = '';
    loadWorlds();
  });

  async function loadWorlds() {
    const response = await fetch('/v1/worlds', { headers: headers() });
    if (!response.ok) {
      controls.status.classList.add('error');
      controls.status.textContent = await errorText(response);
      if (response.status === 401) askForToken();
      return;
    }
    const list = await response.json();
    worlds = new Map(list.worlds.map((world) => [world.name, world]));
    maxLevel = Math.max(0, list.max_level);
    controls.world.replaceChildren(...list.worlds.map((world) => new Option(
      `${world.name} (seed ${world.seed}, d ${world.min_distance}, ${world.algorithm})`, world.name)));
    if (!worlds.has(view.world)) view.world = worlds.has(list.default_world) ? list.default_world : list.worlds[0]?.name || '';
    syncControls();
    requestRender();
  }

  // ---- For tests and scripts: the view and the points drawn ----------------

  window.scallopViewer = {
    // {world, x, y, z, level, rect: [x0, y0, x1, y1], idle, renderMilliseconds}:
    // idle once every tile the view needs is drawn; the last frame's time.
    state: () => ({
      world: view.world, x: view.x, y: view.y, z: view.z, level: drawn.level, rect: drawn.rect,
      idle: drawn.idle && !renderPending, renderMilliseconds,
    }),
    // The points drawn whose centres lie in state().rect: [{id, x, y}], and a
    // layered world's `layer` (its number) on each; hidden layers' are not drawn.
    drawnPoints: () => drawn.shown.map((k) => {
      const point = { id: pointId(k), x: grid.xs[k], y: grid.ys[k] };
      if (layerOf(k) >= 0) point.layer = layerOf(k);
      return point;
    }),
    // What the background shows at (x, y): the nearest point's id, F1 and F2.
    nearest: (x, y) => {
      nearestTwo(x, y);
      return nearFirst < 0 ? null : { id: pointId(nearFirst), f1: nearF1, f2: nearF2 };
    },
    setView: (fields) => { Object.assign(view, fields); clampView(); syncControls(); requestRender(); },
    // A layered world's layers as the page knows them: [{name, colour, shown}].
    layers: () => layerStyles().map((style, k) => ({ name: layersOf()[k].name, colour: style.colour, shown: style.shown })),
    panBy, zoomAt,
  };

  readFragment();
  loadWorlds();
})();
