// The name of a UAV's export files (src/uavplan/io/export.cpp, file_stem): its id's UTF-8 bytes,
// at most 100, each byte other than [A-Za-z0-9_.-] made '_', and '_' before a leading dot.
export function fileStem(id) {
  const bytes = [...Buffer.from(id, 'utf8').subarray(0, 100)];
  const s = bytes.map((b) => (/[A-Za-z0-9_.-]/.test(String.fromCharCode(b)) ? String.fromCharCode(b) : '_')).join('');
  return s === '' || s[0] === '.' ? `_${s}` : s;
}
