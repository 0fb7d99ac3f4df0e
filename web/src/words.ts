// Counts in plain English: "1 triangle", "2 triangles", "10,000 vertices".

const numberFormat = new Intl.NumberFormat('en-US');

/** `n` with the noun in the number it needs; `plural` defaults to noun + "s". */
export function counted(n: number, noun: string, plural = `${noun}s`): string {
  return `${numberFormat.format(n)} ${n === 1 ? noun : plural}`;
}
