// The shortest decimal that reads back as the f32 `v` (JavaScript's toPrecision rounds the exact
// value correctly; parseFloat then Math.fround reads it back), in positional notation as Rust's
// Display writes an f32: "NaN", "inf", "-inf", "-0", "0.000001", "100000000000000000000".
export function f32Text(v) {
  if (Number.isNaN(v)) return "NaN";
  const sign = v < 0 || Object.is(v, -0) ? "-" : "";
  const a = Math.abs(v);
  if (a === Infinity) return `${sign}inf`;
  if (a === 0) return `${sign}0`;
  let text = "";
  for (let p = 1; p <= 9; p++) {
    text = a.toPrecision(p);
    if (Math.fround(parseFloat(text)) === a) break;
  }
  // The digits without leading or trailing zeros, and the point: the value is 0.digits × 10^point.
  const [mantissa, exponent = "0"] = text.split("e");
  const [int, frac = ""] = mantissa.split(".");
  const all = int + frac;
  const lead = all.length - all.replace(/^0+/, "").length;
  const digits = all.slice(lead).replace(/0+$/, "");
  const point = int.length - lead + Number(exponent);
  if (point <= 0) return `${sign}0.${"0".repeat(-point)}${digits}`;
  if (point >= digits.length) return sign + digits + "0".repeat(point - digits.length);
  return `${sign}${digits.slice(0, point)}.${digits.slice(point)}`;
}
