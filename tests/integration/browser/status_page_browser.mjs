// SPDX-License-Identifier: Apache-2.0
// The status page in a real headless browser (Debian's chromium through
// playwright-core): gnssemud on free ports, the page loaded once, live data
// must arrive without a reload, and the DOM must show the same satellites and
// fix as /api/status for the same epoch. Saves a screenshot as an artifact.
// With --gnssemu, also `gnssemu batch --report` over a static hour (or the
// given config and truth) opened from file://: every chart drawn, no page
// error, the summary's figures those of the run; screenshot report.png.
// With --fleet (and --gnssemu, --nav), a fleet instead: three vehicles of
// tools/senders/swarm_truth.py, one with two receivers, an outage injected
// on one with `gnssemu ctl --vehicle`; the overview table must list every
// receiver in order, show the fault, carry /api/status's fix and satellites
// for the same epoch, and a click on a row or the selector must switch the
// page's summary to that receiver; /api/overview's bad queries are 400.
// Usage: node status_page_browser.mjs --gnssemud PATH --artifacts DIR [--config FILE] [--chromium PATH]
//   [--wait-s S]: watch S seconds more before the screenshot (docs/images: a longer history)
//   [--gnssemu PATH [--report-config FILE --report-truth FILE] [--cn0-reference FILE]]
//   [--sender 'ARGS']: tools/senders/send_truth.py ARGS drives the daemon (docs/images)
//   [--fleet --nav FILE]: the fleet check (with --gnssemu for ctl) instead of the single receiver and report
//   [--driver-dir DIR]: where playwright-core is installed (npm ci from
//   tests/integration/browser/package-lock.json when it is missing there;
//   default: the build dir's browser-driver, as CMake passes it)
// Exit 77 (skip) only when chromium is missing or cannot start; a driver that
// cannot be installed is a failure.
import { spawn, spawnSync } from 'node:child_process';
import dgram from 'node:dgram';
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';
import { createRequire } from 'node:module';

const args = Object.fromEntries(
  process.argv.slice(2).reduce((acc, v, i, all) => (v.startsWith('--') ? [...acc, [v.slice(2), all[i + 1]]] : acc), []));
const chromiumPath = args.chromium || '/usr/bin/chromium';
const here = path.dirname(new URL(import.meta.url).pathname);

function skip(why) {
  console.log(`SKIP: ${why}`);
  process.exit(77);
}
function failNow(why) {
  console.error(`FAIL: ${why}`);
  process.exit(1);
}
if (Number(process.versions.node.split('.')[0]) < 20) {
  failNow(`node ${process.versions.node} is too old: playwright-core 1.65 needs node >= 20`);
}
if (!fs.existsSync(chromiumPath)) skip(`${chromiumPath} not found: chromium cannot start (tools/install-deps.sh installs it)`);

/** playwright-core from driverDir, installed there from the lock file on first use. */
function loadDriver(driverDir) {
  const require = createRequire(path.join(driverDir, 'package.json'));
  try {
    return require('playwright-core');
  } catch {
    // Not installed yet (a clean build dir).
  }
  fs.mkdirSync(driverDir, { recursive: true });
  for (const f of ['package.json', 'package-lock.json']) fs.copyFileSync(path.join(here, f), path.join(driverDir, f));
  const t0 = Date.now();
  const npm = spawnSync('npm', ['ci', '--no-audit', '--no-fund', '--loglevel=error'], { cwd: driverDir, encoding: 'utf8' });
  if (npm.error || npm.status !== 0) {
    failNow(`npm ci in ${driverDir} failed (${npm.error ? npm.error.message : `exit ${npm.status}`}): ${npm.stderr || ''}`);
  }
  console.log(`installed playwright-core in ${driverDir} (${((Date.now() - t0) / 1000).toFixed(1)} s)`);
  return require('playwright-core');
}
const { chromium } = loadDriver(path.resolve(args['driver-dir'] || here));

const tmp = fs.mkdtempSync(path.join(os.tmpdir(), 'gnssemu-status-'));
const artifacts = args.artifacts || tmp;
fs.mkdirSync(artifacts, { recursive: true });
let daemon = null;
let sender = null;
let browser = null;
let log = '';
const waitS = Number(args['wait-s'] || 0);
const deadline = Date.now() + 80000 + waitS * 1000 + ('fleet' in args ? 40000 : 0);  // a fleet waits for four fixes

function fail(msg) {
  throw new Error(msg);
}

async function cleanup() {
  if (sender && sender.exitCode === null) sender.kill('SIGTERM');
  if (browser) await browser.close().catch(() => {});
  if (daemon && daemon.exitCode === null) {
    daemon.kill('SIGTERM');
    await new Promise((r) => { daemon.once('exit', r); setTimeout(r, 5000); });
  }
  fs.rmSync(tmp, { recursive: true, force: true });
}

async function startDaemon() {
  const argv = ['--truth-port', '0', '--status-port', 'free'];
  if (args.config) argv.push('--config', args.config);
  else argv.push('--pty', path.join(tmp, 'gps0'));
  daemon = spawn(args.gnssemud, argv, { stdio: ['ignore', 'pipe', 'pipe'] });
  daemon.stderr.on('data', (d) => { log += d; });
  let out = '';
  return new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`gnssemud printed no status URL:\n${out}\n${log}`)), 20000);
    daemon.stdout.on('data', (d) => {
      out += d;
      const url = /status page (http:\/\/[^\s]+)/.exec(out);
      const truth = /truth input udp ([\d.]+):(\d+)/.exec(out);
      if (url && truth) {
        clearTimeout(timer);
        resolve({ url: url[1], truthPort: Number(truth[2]) });
      }
    });
    daemon.on('exit', (code) => reject(new Error(`gnssemud exited with ${code}:\n${out}\n${log}`)));
  });
}

/** What the page shows, read from the DOM. */
async function domState(page) {
  return page.evaluate(() => ({
    tow: document.body.dataset.tow,
    epoch: Number(document.body.dataset.epoch || 0),
    fixType: document.getElementById('fix-type').dataset.fixType,
    numUsed: document.getElementById('num-used').textContent,
    numTracked: document.getElementById('num-tracked').textContent,
    lat: document.getElementById('lat').textContent,
    lon: document.getElementById('lon').textContent,
    hdop: document.getElementById('hdop').textContent,
    dropped: document.getElementById('truth-dropped').textContent,
    sats: [...document.querySelectorAll('#sat-table tbody tr')].map((tr) => ({ prn: Number(tr.dataset.prn), state: tr.dataset.state })),
    skyPoints: Chart.getChart('sky').data.datasets.filter((d) => !d.gridLine && !d.mask)
      .flatMap((d) => d.data.map((p) => p.prn)).sort((a, b) => a - b),
    cn0Bars: [...Chart.getChart('cn0').data.labels].sort(),
    marker: window.__loadedOnce === true,
    conn: document.getElementById('conn').textContent,
  }));
}

async function main() {
  try {
    // playwright gives each launch a fresh --user-data-dir.
    browser = await chromium.launch({
      executablePath: chromiumPath,
      headless: true,
      args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
             '--disable-component-update', '--disable-sync'],
    });
  } catch (e) {
    await cleanup();
    skip(`${chromiumPath} cannot start: ${e.message.split('\n')[0]}`);
  }
  const { url, truthPort } = await startDaemon();
  console.log(`status page ${url}, truth port ${truthPort}`);
  if (args.sender) {
    const script = path.resolve(here, '..', '..', '..', 'tools', 'senders', 'send_truth.py');
    sender = spawn('python3', [script, '--port', String(truthPort), ...args.sender.split(' ')], { stdio: 'ignore' });
  }
  const context = await browser.newContext({ viewport: { width: 1400, height: 1900 } });
  const page = await context.newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  await page.goto(url, { waitUntil: 'load' });
  await page.evaluate(() => { window.__loadedOnce = true; });

  // A malformed truth packet: the page must count it as the API does.
  const sock = dgram.createSocket('udp4');
  await new Promise((r) => sock.send('{"version": 1, "lla": ', truthPort, '127.0.0.1', r));
  sock.close();

  // Live data: the shown epoch advances at least three times without a reload.
  await page.waitForFunction(() => document.getElementById('conn').textContent === 'live', null, { timeout: 15000 });
  const first = (await domState(page)).epoch;
  await page.waitForFunction((e0) => Number(document.body.dataset.epoch || 0) >= e0 + 3, first, { timeout: 15000 });
  await page.waitForFunction(() => document.getElementById('fix-type').dataset.fixType === '3', null, { timeout: 15000 });
  await page.waitForFunction(() => document.getElementById('truth-dropped').textContent !== '0', null, { timeout: 15000 });

  // The DOM against /api/status of the same epoch.
  let matched = false;
  for (let attempt = 0; attempt < 20 && !matched && Date.now() < deadline; attempt++) {
    const dom = await domState(page);
    const api = await (await fetch(`${url}api/status?history=0`)).json();
    if (String(api.epoch.tow_s) !== dom.tow) {
      await new Promise((r) => setTimeout(r, 150));
      continue;
    }
    matched = true;
    if (!dom.marker) fail('the page was reloaded');
    if (dom.fixType !== String(api.fix.type)) fail(`fix type: DOM ${dom.fixType}, API ${api.fix.type}`);
    if (dom.numUsed !== String(api.fix.num_used)) fail(`used: DOM ${dom.numUsed}, API ${api.fix.num_used}`);
    if (dom.numTracked !== String(api.fix.num_tracked)) fail(`tracked: DOM ${dom.numTracked}, API ${api.fix.num_tracked}`);
    if (dom.lat !== `${api.fix.lat_deg.toFixed(7)}°`) fail(`lat: DOM ${dom.lat}, API ${api.fix.lat_deg}`);
    if (dom.lon !== `${api.fix.lon_deg.toFixed(7)}°`) fail(`lon: DOM ${dom.lon}, API ${api.fix.lon_deg}`);
    if (dom.hdop !== api.fix.dop.hdop.toFixed(2)) fail(`hdop: DOM ${dom.hdop}, API ${api.fix.dop.hdop}`);
    if (dom.dropped !== String(api.truth.dropped)) fail(`truth drops: DOM ${dom.dropped}, API ${api.truth.dropped}`);
    const apiSats = api.satellites.map((s) => ({ prn: s.prn, state: s.state }));
    if (JSON.stringify(dom.sats) !== JSON.stringify(apiSats)) {
      fail(`satellites: DOM ${JSON.stringify(dom.sats)}, API ${JSON.stringify(apiSats)}`);
    }
    const apiPrns = api.satellites.map((s) => s.prn).sort((a, b) => a - b);
    if (JSON.stringify(dom.skyPoints) !== JSON.stringify(apiPrns)) fail(`sky plot PRNs ${dom.skyPoints} vs ${apiPrns}`);
    const barPrns = api.satellites.filter((s) => s.state !== 'below_mask').map((s) => s.sat).sort();  // bars are labelled G07, R12, ...
    if (JSON.stringify(dom.cn0Bars) !== JSON.stringify(barPrns)) fail(`C/N0 bars ${dom.cn0Bars} vs ${barPrns}`);
    if (api.satellites.length < 4 || api.fix.num_used < 4) fail(`too few satellites for a meaningful check: ${api.satellites.length}`);
    console.log(`epoch tow ${dom.tow}: ${apiSats.length} satellites, fix ${api.fix.type_name} with ${api.fix.num_used} used: DOM = API`);
  }
  if (!matched) fail('the DOM never showed the epoch /api/status returned');
  if (!(await page.isHidden('#panel-overview'))) fail('one receiver, yet the overview table is shown');
  if (errors.length) fail(`page errors: ${errors.join('; ')}`);
  if (waitS > 0) await new Promise((r) => setTimeout(r, waitS * 1000));
  const shot = path.join(artifacts, 'status_page.png');
  await page.screenshot({ path: shot, fullPage: true });
  console.log(`screenshot ${shot}`);
}

/** The fleet's receivers, in the order the overview must show them (vehicle, receiver). */
const FLEET = [['v0', 'gps1'], ['v0', 'gps2'], ['v1', 'gps1'], ['v2', 'gps1']];
const FAULTY = 'v1';  // the vehicle given an outage

function fleetConfig() {
  const sock = path.join(tmp, 'ctl.sock');
  const receivers = (v, names) => names.map((r) => `[[vehicle.receiver]]
name = "${r}"
${r === 'gps2' ? 'lever_arm_m = [0.0, 30.0, 0.0]\nseed = 7\n' : ''}[[vehicle.receiver.output]]
name = "${v}-${r}"
type = "file"
path = "${path.join(tmp, `${v}-${r}.nmea`)}"
`).join('');
  const vehicles = ['v0', 'v1', 'v2'].map((v) => `[[vehicle]]\nid = "${v}"\n` +
    receivers(v, FLEET.filter(([x]) => x === v).map(([, r]) => r))).join('');
  const file = path.join(tmp, 'fleet.toml');
  fs.writeFileSync(file, `[origin]
lat_deg = 48.8738
lon_deg = 2.2950
height_m = 100.0
[nav]
file = "${path.resolve(args.nav)}"
[time]
start = "2022-01-01T01:00:00"
[receiver]
rate_hz = 2.0
[truth]
timeout_s = 3.0
[demo]
enabled = false
[control]
socket = "${sock}"
${vehicles}`);
  return { file, sock };
}

const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

async function getJson(url) {
  const r = await fetch(url);
  if (!r.ok) fail(`${url}: HTTP ${r.status} ${await r.text()}`);
  return r.json();
}

/** The overview rows as the DOM shows them. */
async function overviewDom(page) {
  return page.evaluate(() => [...document.querySelectorAll('#overview-table tbody tr')].map((tr) => ({
    vehicle: tr.dataset.vehicle, receiver: tr.dataset.receiver, fixType: Number(tr.dataset.fixType),
    numUsed: Number(tr.dataset.numUsed), faults: Number(tr.dataset.faults), epochs: Number(tr.dataset.epochs),
    picked: tr.className === 'picked', cells: [...tr.cells].map((td) => td.textContent),
  })));
}

/** The page's summary (header and Fix panel) against /api/status of v/r at the same epoch. */
async function summaryIs(page, url, v, r) {
  for (let attempt = 0; attempt < 40 && Date.now() < deadline; attempt++) {
    const dom = await domState(page);
    const api = await getJson(`${url}api/status?history=0&vehicle=${v}&receiver=${r}`);
    if (String(api.epoch.tow_s) !== dom.tow) {
      await sleep(100);
      continue;
    }
    if (dom.fixType !== String(api.fix.type)) fail(`${v}/${r} summary fix type ${dom.fixType}, API ${api.fix.type}`);
    if (dom.numUsed !== String(api.fix.num_used)) fail(`${v}/${r} summary used ${dom.numUsed}, API ${api.fix.num_used}`);
    const deg = (x) => (x === null ? '—' : `${x.toFixed(7)}°`);
    if (dom.lat !== deg(api.fix.lat_deg)) fail(`${v}/${r} summary lat ${dom.lat}, API ${api.fix.lat_deg}`);
    if (dom.lon !== deg(api.fix.lon_deg)) fail(`${v}/${r} summary lon ${dom.lon}, API ${api.fix.lon_deg}`);
    return { fixType: api.fix.type, numUsed: api.fix.num_used, lat: dom.lat, lon: dom.lon,
             latDeg: api.fix.lat_deg, lonDeg: api.fix.lon_deg };
  }
  return fail(`${v}/${r}: the summary never showed the epoch /api/status returned`);
}

async function checkFleet() {
  if (!args.nav || !args.gnssemu) fail('--fleet needs --nav and --gnssemu');
  try {
    browser = await chromium.launch({ executablePath: chromiumPath, headless: true,
      args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run', '--disable-background-networking',
             '--disable-component-update', '--disable-sync'] });
  } catch (e) {
    await cleanup();
    skip(`${chromiumPath} cannot start: ${e.message.split('\n')[0]}`);
  }
  const { file, sock } = fleetConfig();
  args.config = file;
  const { url, truthPort } = await startDaemon();
  console.log(`fleet status page ${url}, truth port ${truthPort}`);
  const script = path.resolve(here, '..', '..', '..', 'tools', 'senders', 'swarm_truth.py');
  sender = spawn('python3', [script, '--port', String(truthPort), '--count', '3', '--formation', 'line',
                             '--spacing', '300', '--speed', '0', '--rate', '5'], { stdio: 'ignore' });

  // The HTTP side: bad queries are refused by name.
  for (const [q, want] of [['limit=0', 'limit must be a whole number in [1, 1000]'], ['limit=x', 'limit must be'],
                           ['sort=speed', 'sort must be one of name, fix'], ['order=up', 'order must be asc or desc'],
                           ['vehicle=v0', "unknown query parameter 'vehicle'"], ['offset=-1', 'offset must be']]) {
    const r = await fetch(`${url}api/overview?${q}`);
    const body = await r.text();
    if (r.status !== 400 || !body.includes(want)) fail(`/api/overview?${q}: ${r.status} ${body}`);
  }

  // Every receiver with a 3D fix before the fault.
  const t0 = Date.now();
  for (;;) {
    const o = await getJson(`${url}api/overview`);
    if (o.total !== FLEET.length || o.rows.length !== FLEET.length) fail(`overview total ${o.total}, rows ${o.rows.length}`);
    if (o.rows.every((x) => x.fix_type === 3 && x.truth_source === 'simulator')) break;
    if (Date.now() - t0 > 40000) fail(`no 3D fix on every receiver: ${JSON.stringify(o.rows.map((x) => [x.vehicle, x.receiver, x.fix_type]))}`);
    await sleep(250);
  }
  console.log(`every receiver fixed after ${((Date.now() - t0) / 1000).toFixed(1)} s`);
  const scen = path.join(tmp, 'outage.toml');
  fs.writeFileSync(scen, '[[event]]\ntype = "outage"\nstart_s = 0\nduration_s = 600\n');
  const ctl = spawnSync(args.gnssemu, ['ctl', '--socket', sock, '--vehicle', FAULTY, 'inject', scen], { encoding: 'utf8' });
  if (ctl.status !== 0) fail(`ctl inject: ${ctl.status} ${ctl.stderr}`);

  const page = await (await browser.newContext({ viewport: { width: 1400, height: 2100 } })).newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  await page.goto(url, { waitUntil: 'load' });
  await page.waitForSelector('#panel-overview', { state: 'visible', timeout: 10000 });
  await page.waitForFunction((n) => document.querySelectorAll('#overview-table tbody tr').length === n, FLEET.length,
                             { timeout: 10000 });
  // One row per receiver, ordered by vehicle then receiver; the first is the one shown.
  let rows = await overviewDom(page);
  const ids = rows.map((x) => `${x.vehicle}/${x.receiver}`);
  if (JSON.stringify(ids) !== JSON.stringify(FLEET.map(([v, r]) => `${v}/${r}`))) fail(`overview rows ${ids}`);
  if (!rows[0].picked || rows.slice(1).some((x) => x.picked)) fail(`the picked row is not v0/gps1: ${JSON.stringify(rows)}`);

  // The faulty vehicle's row shows its outage (and has lost its fix); the others none.
  await page.waitForFunction((v) => {
    const tr = document.querySelector(`#overview-table tbody tr[data-vehicle="${v}"]`);
    return tr && tr.dataset.faults === '1' && tr.dataset.fixType !== '3';  // an outage: no fix or dead reckoning
  }, FAULTY, { timeout: 15000 });
  // The others keep (or, on a loaded machine whose sender stalled, regain) their 3D fix.
  await page.waitForFunction((v) => [...document.querySelectorAll('#overview-table tbody tr')]
    .every((tr) => tr.dataset.vehicle === v || tr.dataset.fixType === '3'), FAULTY, { timeout: 15000 })
    .catch(() => {});
  rows = await overviewDom(page);
  for (const x of rows) {
    const faulty = x.vehicle === FAULTY;
    if (faulty && !/^outage \d+$/.test(x.cells[6])) fail(`${x.vehicle}/${x.receiver} faults cell '${x.cells[6]}'`);
    if (!faulty && (x.faults !== 0 || x.cells[6] !== '—')) fail(`${x.vehicle}/${x.receiver} shows a fault: '${x.cells[6]}'`);
    if (faulty && !['no fix', 'dead reckoning'].includes(x.cells[1])) {
      fail(`${x.vehicle}/${x.receiver} fix cell '${x.cells[1]}' under an outage`);
    }
    if (!faulty && x.cells[1] !== '3D') fail(`${x.vehicle}/${x.receiver} fix cell '${x.cells[1]}'`);
  }
  console.log(`overview: ${ids.join(', ')}; ${FAULTY} shows '${rows.find((x) => x.vehicle === FAULTY).cells[6]}'`);

  // Each row's fix type and satellites are /api/status's of the same epoch:
  // the row is read as soon as the page refreshes it, /api/status right after.
  const rowOf = (v, r) => `#overview-table tbody tr[data-vehicle="${v}"][data-receiver="${r}"]`;
  for (const [v, r] of FLEET) {
    let same = false;
    for (let attempt = 0; attempt < 10 && !same && Date.now() < deadline; attempt++) {
      const e0 = (await overviewDom(page)).find((x) => x.vehicle === v && x.receiver === r).epochs;
      await page.waitForFunction(([sel, e]) => Number(document.querySelector(sel).dataset.epochs) !== e,
                                 [rowOf(v, r), e0], { timeout: 5000, polling: 20 });
      const api = await getJson(`${url}api/status?history=0&vehicle=${v}&receiver=${r}`);
      const row = (await overviewDom(page)).find((x) => x.vehicle === v && x.receiver === r);
      if (api.epoch.count !== row.epochs) continue;  // an epoch between the two reads
      same = true;
      if (row.fixType !== api.fix.type) fail(`${v}/${r}: row fix ${row.fixType}, API ${api.fix.type}`);
      if (row.numUsed !== api.fix.num_used) fail(`${v}/${r}: row used ${row.numUsed}, API ${api.fix.num_used}`);
      const sats = `${api.fix.num_used} / ${api.fix.num_tracked} / ${api.fix.num_visible}`;
      if (row.cells[2] !== sats) fail(`${v}/${r}: row sats '${row.cells[2]}', API '${sats}'`);
      if (api.fix.type === 3 && api.fix.num_used < 4) fail(`${v}/${r}: a 3D fix with ${api.fix.num_used} satellites`);
    }
    if (!same) fail(`${v}/${r}: the row never showed the epoch /api/status returned`);
  }
  console.log('overview rows = /api/status (fix type, satellites) for every receiver');

  // The summary follows the row clicked, then the selector.
  await page.waitForFunction(() => document.getElementById('conn').textContent === 'live', null, { timeout: 15000 });
  const before = await summaryIs(page, url, 'v0', 'gps1');
  await page.evaluate(() => { window.__sameDocument = true; });
  await page.click(`#overview-table tbody tr[data-vehicle="${FAULTY}"]`);
  await page.waitForURL((u) => u.search === `?vehicle=${FAULTY}&receiver=gps1`, { timeout: 10000 });
  await page.waitForFunction(() => document.getElementById('conn').textContent === 'live', null, { timeout: 15000 });
  const faulty = await summaryIs(page, url, FAULTY, 'gps1');
  if (faulty.fixType === 3 || before.fixType !== 3 || (faulty.lat === before.lat && faulty.lon === before.lon)) {
    fail(`the summary did not switch to ${FAULTY}/gps1: before ${JSON.stringify(before)}, after ${JSON.stringify(faulty)}`);
  }
  await page.waitForFunction((v) => document.querySelector(`#overview-table tbody tr.picked[data-vehicle="${v}"]`), FAULTY,
                             { timeout: 10000 });
  await page.selectOption('#receiver-select', { label: 'v2/gps1' });
  await page.waitForURL((u) => u.search === '?vehicle=v2&receiver=gps1', { timeout: 10000 });
  await page.waitForFunction(() => document.getElementById('conn').textContent === 'live', null, { timeout: 15000 });
  const v2 = await summaryIs(page, url, 'v2', 'gps1');
  // v0 and v2 fly 600 m apart (line abreast, 300 m spacing).
  const apartM = Math.hypot((v2.latDeg - before.latDeg) * 111195,
                            (v2.lonDeg - before.lonDeg) * 111195 * Math.cos(before.latDeg * Math.PI / 180));
  if (v2.fixType !== 3 || Math.abs(apartM - 600) > 30) {
    fail(`the summary did not switch to v2/gps1: ${JSON.stringify(v2)}, ${apartM.toFixed(1)} m from v0/gps1's`);
  }
  console.log(`summary: v0/gps1 fix ${before.fixType} -> row click ${FAULTY}/gps1 fix ${faulty.fixType}` +
              ` -> selector v2/gps1 fix ${v2.fixType}, ${apartM.toFixed(1)} m from v0/gps1's position`);

  // Paging (?rows=3): 1–3 of 4 with previous disabled, next shows the fourth, previous goes back.
  const rowIds = async () => (await overviewDom(page)).map((x) => `${x.vehicle}/${x.receiver}`);
  const rowsShown = (n) => page.waitForFunction((k) => document.querySelectorAll('#overview-table tbody tr').length === k,
                                                n, { timeout: 10000 });
  await page.goto(`${url}?rows=3`, { waitUntil: 'load' });
  await page.waitForSelector('#overview-pages', { state: 'visible', timeout: 10000 });
  await rowsShown(3);
  const page1 = await rowIds();
  const count1 = (await page.textContent('#overview-count')).trim();
  if (count1 !== `(1–3 of ${FLEET.length})` || !(await page.isDisabled('#overview-prev')) ||
      (await page.isDisabled('#overview-next'))) fail(`first page: ${count1}, rows ${page1}`);
  await page.click('#overview-next');
  await rowsShown(1);
  const page2 = await rowIds();
  const count2 = (await page.textContent('#overview-count')).trim();
  const want = FLEET.map(([v, r]) => `${v}/${r}`);
  if (count2 !== `(4–4 of ${FLEET.length})` || !(await page.isDisabled('#overview-next')) ||
      JSON.stringify([...page1, ...page2]) !== JSON.stringify(want)) {
    fail(`second page: ${count2}, rows ${page2} after ${page1}`);
  }
  await page.click('#overview-prev');
  await rowsShown(3);
  console.log(`paging, 3 rows a page: ${count1} ${page1.join(', ')} | next ${count2} ${page2.join(', ')} | previous back`);

  // Sorting orders the whole fleet before paging: the name column twice
  // (ascending, then descending) puts v2/gps1 first and v0/gps1 on page 2,
  // where reordering page 1 alone would keep v0/gps1 on it.
  const firstRow = (id) => page.waitForFunction((k) => {
    const tr = document.querySelector('#overview-table tbody tr');
    return tr && `${tr.dataset.vehicle}/${tr.dataset.receiver}` === k;
  }, id, { timeout: 10000 });
  await page.click('#overview-table th[data-key="name"]');
  await firstRow('v0/gps1');
  await page.click('#overview-table th[data-key="name"]');
  await firstRow('v2/gps1');
  await rowsShown(3);
  const sorted1 = await rowIds();
  const api = await getJson(`${url}api/overview?sort=name&order=desc&limit=3`);
  await page.click('#overview-next');
  await rowsShown(1);
  const sorted2 = await rowIds();
  const wantDesc = [...want].reverse();
  if (JSON.stringify([...sorted1, ...sorted2]) !== JSON.stringify(wantDesc) ||
      JSON.stringify(api.rows.map((x) => `${x.vehicle}/${x.receiver}`)) !== JSON.stringify(wantDesc.slice(0, 3))) {
    fail(`name descending: page 1 ${sorted1}, page 2 ${sorted2}, /api/overview ${JSON.stringify(api.rows.map((x) => x.vehicle + '/' + x.receiver))}`);
  }
  console.log(`sorted by name, descending, 3 rows a page: ${sorted1.join(', ')} | next ${sorted2.join(', ')}`);
  if (errors.length) fail(`page errors: ${errors.join('; ')}`);
  const shot = path.join(artifacts, 'status_fleet.png');
  await page.screenshot({ path: shot, fullPage: true });
  console.log(`screenshot ${shot}`);
}

/** gnssemu batch --report, the report in the browser, its screenshot. */
async function checkReport() {
  const source = path.resolve(here, '..', '..', '..');
  let truth = args['report-truth'];
  if (!truth) {
    truth = path.join(tmp, 'static.csv');
    fs.writeFileSync(truth, 'gps_week,tow_s,lat_deg,lon_deg,height_m\n2190,522000,48.8738,2.2950,100.0\n' +
                            '2190,525600,48.8738,2.2950,100.0\n');
  }
  const config = args['report-config'] || path.join(source, 'config', 'default.toml');
  const reference = args['cn0-reference'] || path.join(source, 'tests', 'data', 'receiver-logs', 'ublox-8-excerpt.log');
  const dir = path.join(tmp, 'report');
  const run = spawnSync(args.gnssemu, ['batch', '--config', config, '--truth', truth, '--report', dir,
                                       '--cn0-reference', reference], { encoding: 'utf8' });
  if (run.status !== 0) fail(`gnssemu batch --report exited with ${run.status}: ${run.stderr}`);
  const fixes = /fixes (\d+)/.exec(run.stderr);
  const epochs = /epochs (\d+)/.exec(run.stderr);
  const page = await (await browser.newContext({ viewport: { width: 1400, height: 1000 } })).newPage();
  const errors = [];
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('request', (r) => { if (!r.url().startsWith('file:') && !r.url().startsWith('data:')) errors.push(`fetched ${r.url()}`); });
  await page.goto(`file://${path.join(dir, 'report.html')}`, { waitUntil: 'load' });
  const shown = await page.evaluate(() => {
    const charts = [...document.querySelectorAll('canvas')].map((c) => Chart.getChart(c)).filter((c) => c);
    const points = charts.map((c) => c.data.datasets.reduce((n, d) => n + d.data.length, 0));
    const kv = Object.fromEntries([...document.querySelectorAll('#summary tr')]
      .map((tr) => [tr.querySelector('th').textContent, tr.querySelector('td').textContent]));
    return { ids: charts.map((c) => c.canvas.id), points, kv };
  });
  if (errors.length) fail(`report page errors: ${errors.join('; ')}`);
  for (const id of ['sky', 'cn0-el', 'error', 'accuracy', 'cdf', 'scatter', 'sats']) {
    const i = shown.ids.indexOf(id);
    if (i < 0) fail(`report: no chart '${id}' (charts: ${shown.ids})`);
    if (shown.points[i] === 0) fail(`report: chart '${id}' is empty`);
  }
  if (!epochs || shown.kv.epochs !== epochs[1]) fail(`report: epochs ${shown.kv.epochs}, batch printed ${epochs && epochs[1]}`);
  if (!fixes || !shown.kv.fixes.startsWith(`${fixes[1]} `)) fail(`report: fixes ${shown.kv.fixes}, batch printed ${fixes && fixes[1]}`);
  const shot = path.join(artifacts, 'report.png');
  await page.screenshot({ path: shot, fullPage: true });
  console.log(`report: ${shown.ids.length} charts, ${shown.kv.epochs} epochs; screenshot ${shot}`);
}

try {
  if ('fleet' in args) {
    await checkFleet();
  } else {
    await main();
    if (args.gnssemu) await checkReport();
  }
  await cleanup();
  console.log('1 passed, 0 failed');
} catch (e) {
  console.error(`FAIL: ${e.message}`);
  console.error(log.split('\n').slice(-20).join('\n'));
  await cleanup();
  process.exit(1);
}
