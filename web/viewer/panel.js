// The HTML around the 3D view: error banner, status line, legend, the drive
// section (tool selector, take / release), and the tools, free bodies and
// contacts tables.
// All text from the bridge goes in through textContent, never as HTML.

import { FEATURE_COLORS, FORCE_ARROW, PROXY_GHOST, REVERSING_ARROW } from './colors.js';
import { FORCE_SCALE_M_PER_N, REVERSING_MIN_LENGTH_M, REVERSING_SCALE } from './frame_view.js';

const MAX_POINTS_LISTED = 3;

export class Panel {
  /** onTake() and onRelease() are called by the Take / Release buttons. */
  constructor({ onTake, onRelease }) {
    const byId = (id) => document.getElementById(id);
    this.banner = byId('banner');
    this.statusLine = byId('status-line');
    this.toolSelect = byId('tool-select');
    this.driveText = byId('drive-state');
    this.toolsBody = byId('tools-body');
    this.bodiesSection = byId('bodies-section');
    this.bodiesBody = byId('bodies-body');
    this.contactsBody = byId('contacts-body');
    this.noContacts = byId('no-contacts');
    this.bannerMessages = new Map(); // source -> message, in arrival order
    this.statusLineText = '';

    byId('take-button').addEventListener('click', onTake);
    byId('release-button').addEventListener('click', onRelease);
    buildLegend(byId('legend'));
  }

  /** Shows (or with null clears) the banner message of one source of trouble. */
  setBanner(source, message) {
    if (message) this.bannerMessages.set(source, message);
    else this.bannerMessages.delete(source);
    const text = [...this.bannerMessages.values()].join(' — ');
    this.banner.textContent = text;
    this.banner.hidden = text === '';
  }

  setStatusLine(text) {
    if (text === this.statusLineText) return;
    this.statusLineText = text;
    this.statusLine.textContent = text;
  }

  /** The banner and status line together, as viewerState.status. */
  statusText() {
    return [this.banner.textContent, this.statusLineText].filter(Boolean).join(' | ');
  }

  /** Refills the tool selector if the names changed, keeping the choice. */
  setToolNames(names) {
    const current = [...this.toolSelect.options].map((o) => o.value);
    if (current.join('\n') === names.join('\n')) return;
    const chosen = this.toolSelect.value;
    this.toolSelect.replaceChildren(...names.map((name) => new Option(name, name)));
    if (names.includes(chosen)) this.toolSelect.value = chosen;
  }

  selectedTool() {
    return this.toolSelect.value || null;
  }

  showDrive(heldTool, driveState, message) {
    const what = heldTool ? `Driving ${heldTool}.` : 'Not driving.';
    const detail = [driveState, message].filter(Boolean).join(': ');
    this.driveText.textContent = detail ? `${what} (${detail})` : what;
    this.driveText.classList.toggle('held', Boolean(heldTool));
  }

  /** tools: viewerState.tools. */
  showTools(tools) {
    this.toolsBody.replaceChildren(...Object.entries(tools).map(([name, tool]) => tableRow([
      name,
      tool.holder || '—',
      formatVector(tool.force_n, 1, 2),
      tool.force_magnitude_n.toFixed(2) + (tool.force_clamped ? ' (clamped)' : ''),
    ])));
  }

  /** bodies: viewerState.bodies; the section shows only when the scene has some. */
  showBodies(bodies) {
    const entries = Object.entries(bodies);
    this.bodiesSection.hidden = entries.length === 0;
    this.bodiesBody.replaceChildren(...entries.map(([name, body]) => tableRow([
      name,
      body.touching_tools.join(', ') || '—',
      body.held ? 'yes' : 'no',
    ])));
  }

  /** contacts: viewerState.contacts. */
  showContacts(contacts) {
    this.contactsBody.replaceChildren(...contacts.map((c) => tableRow([
      c.tool,
      c.object,
      c.kind,
      formatNumber(c.depth_m * 1000, 2),
      formatVector(c.reversing_vector_m, 1000, 2),
      formatPoints(c.points),
    ])));
    this.noContacts.hidden = contacts.length > 0;
  }
}

function tableRow(cells) {
  const row = document.createElement('tr');
  for (const text of cells) {
    const cell = document.createElement('td');
    cell.textContent = text;
    row.append(cell);
  }
  return row;
}

function formatNumber(x, digits) {
  return Number.isFinite(x) ? x.toFixed(digits) : '?';
}

/** [x, y, z] times `scale`, e.g. "(1.00, -2.00, 0.50)". */
function formatVector(v, scale, digits) {
  if (!Array.isArray(v)) return '?';
  return `(${v.map((x) => formatNumber(x * scale, digits)).join(', ')})`;
}

/** The first few points in mm, rounded to 0.1 mm. */
function formatPoints(points) {
  const shown = points.slice(0, MAX_POINTS_LISTED).map((p) => formatVector(p, 1000, 1));
  const more = points.length - shown.length;
  return shown.join(' ') + (more > 0 ? ` +${more} more` : '');
}

/** The legend box: the six feature colours, the two arrows and the ghost. */
function buildLegend(box) {
  const entries = [
    ['vertex', FEATURE_COLORS.tool.vertices, 'tool vertex'],
    ['edge', FEATURE_COLORS.tool.edges, 'tool edge'],
    ['face', FEATURE_COLORS.tool.faces, 'tool face'],
    ['vertex', FEATURE_COLORS.object.vertices, 'object vertex'],
    ['edge', FEATURE_COLORS.object.edges, 'object edge'],
    ['face', FEATURE_COLORS.object.faces, 'object face'],
    ['arrow', FORCE_ARROW, `force (1 N = ${FORCE_SCALE_M_PER_N * 100} cm)`],
    ['arrow', REVERSING_ARROW,
      `reversing vector (×${REVERSING_SCALE}, min ${REVERSING_MIN_LENGTH_M * 1000} mm)`],
    ['face', PROXY_GHOST, 'tool proxy (ghost)'],
  ];
  const title = document.createElement('h2');
  title.textContent = 'Legend';
  const list = document.createElement('ul');
  for (const [shape, color, label] of entries) {
    const item = document.createElement('li');
    const swatch = document.createElement('span');
    swatch.className = `swatch ${shape}`;
    swatch.style.setProperty('--swatch', color);
    item.append(swatch, label);
    list.append(item);
  }
  box.replaceChildren(title, list);
}
