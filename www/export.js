// @ts-check
// Export of a run's results: JSON lines in the project's track format (one estimate per frame,
// as `lanepf track` writes them) and CSV of the lane parameters every tracker shares.

export const CSV_COLUMNS = ['frame', 'valid', 'lateral_offset_m', 'heading_rad', 'curvature_per_m',
  'lane_width_m', 'ms'];

/**
 * One JSON object per line, newline-terminated.
 * @param {object[]} results
 */
export function toJsonLines(results) {
  return results.map((r) => `${JSON.stringify(r)}\n`).join('');
}

/** @param {unknown} v */
const csvField = (v) => {
  const s = String(v);
  return /[",\n]/.test(s) ? `"${s.replace(/"/g, '""')}"` : s;
};

/**
 * A header row and one row per frame.
 * @param {Record<string, unknown>[]} results
 */
export function toCsv(results) {
  const rows = results.map((r) => CSV_COLUMNS.map((c) => csvField(r[c])).join(','));
  return `${[CSV_COLUMNS.join(','), ...rows].join('\n')}\n`;
}

/**
 * Saves `text` as a file through the browser's download (nothing leaves the machine).
 * @param {string} name
 * @param {string} text
 * @param {string} type
 */
export function download(name, text, type) {
  const url = URL.createObjectURL(new Blob([text], { type }));
  const a = document.createElement('a');
  a.href = url;
  a.download = name;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 1000);
}
