// A foxglove.Grid message of a terrain map checked against the map's size: the five cell
// fields, column count, row and cell strides, the cells' byte count. Returns the height of
// cell (i, j) (column i along x, row j along y), or null when the layout is wrong.
export function checkGridLayout(topic, g, want, fail) {
  const field = (name) => g.fields.find((f) => f.name === name);
  for (const name of ["height", "variance", "count", "max", "min"])
    if (!field(name)) fail(`${topic}: no cell field ${name}`);
  const data = Buffer.from(g.data, "base64");
  if (g.column_count !== want.nx) fail(`${topic}: column_count ${g.column_count}, the map has nx ${want.nx}`);
  if (g.row_stride !== g.column_count * g.cell_stride) fail(`${topic}: row_stride ${g.row_stride} != columns x cell_stride`);
  if (data.length !== want.nx * want.ny * g.cell_stride) {
    fail(`${topic}: ${data.length} bytes of cells, expected ${want.nx} x ${want.ny} x ${g.cell_stride}`);
    return null;
  }
  const height = field("height");
  if (!height) return null;
  return (i, j) => data.readFloatLE(j * g.row_stride + i * g.cell_stride + height.offset);
}
