// Every colour the viewer draws with, in one place (CSS colour strings, which
// THREE.Color and the 2D canvas both accept).
//
// Scene background: dark slate #1d2127, so highlights and arrows stand out.
//
// Object faces are coloured by material: MATERIAL_PALETTE[material index % 8].
// Muted tones, none of them close to a highlight or arrow colour:
//   0 light grey #b4b8be   1 sage #8fae8b      2 tan #c9a97f     3 lavender #9a8fc0
//   4 steel teal #6f9fae   5 dusty rose #b98585 6 olive #a3a36b   7 slate #7d8794
//
// Contact features, six distinct colours (three per side):
//   tool side:   vertex yellow #ffe600   edge orange #ff8c00   face red     #ff2a2a
//   object side: vertex cyan   #00e5ff   edge blue   #2f6bff   face magenta #ff00d4
//
// Arrows:
//   force            green #3ddc5a (at the tool's device origin, 1 N -> 2 cm)
//   reversing vector white #ffffff (from the first contact point, x5, at least 5 mm)
//
// Tool proxy ghost: translucent pale blue #a8c8ff.
// Strip chart: one line colour per tool, TOOL_LINE_COLORS[tool order % 6].

export const BACKGROUND = '#1d2127';
export const GRID_MAJOR = '#4a525c';
export const GRID_MINOR = '#2e343b';

export const MATERIAL_PALETTE = [
  '#b4b8be', '#8fae8b', '#c9a97f', '#9a8fc0',
  '#6f9fae', '#b98585', '#a3a36b', '#7d8794',
];

export const FEATURE_COLORS = {
  tool: { vertices: '#ffe600', edges: '#ff8c00', faces: '#ff2a2a' },
  object: { vertices: '#00e5ff', edges: '#2f6bff', faces: '#ff00d4' },
};

export const FORCE_ARROW = '#3ddc5a';
export const REVERSING_ARROW = '#ffffff';
export const PROXY_GHOST = '#a8c8ff';

export const TOOL_LINE_COLORS = [
  '#3ddc5a', '#ffb000', '#5aa9ff', '#ff6f91', '#c6a0ff', '#7fffd4',
];

/** The material colour for a material index (any integer; wraps around). */
export function materialColor(index) {
  const n = MATERIAL_PALETTE.length;
  const i = Number.isInteger(index) ? ((index % n) + n) % n : 0;
  return MATERIAL_PALETTE[i];
}
