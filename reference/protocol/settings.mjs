import { InputError } from './errors.mjs';

// An adapter's settings: declared once as a table of rows
//   { key, kind: 'integer'|'number'|'boolean'|'choice', unit, min, max, choices, default, what }
// from which hello's "settings" is written and every load's "settings" is checked and completed.

export function describeSettings(table) {
  return table.map((row) => {
    const out = { key: row.key, kind: row.kind, unit: row.unit ?? '', default: row.default, what: row.what };
    if (row.kind === 'integer' || row.kind === 'number') {
      out.min = row.min;
      out.max = row.max;
    }
    if (row.kind === 'choice') out.choices = row.choices;
    return out;
  });
}

function checkValue(row, value) {
  const where = `setting "${row.key}"`;
  switch (row.kind) {
    case 'boolean':
      if (typeof value !== 'boolean') throw new InputError(`${where} must be true or false, not ${JSON.stringify(value)}`);
      return value;
    case 'choice':
      if (!row.choices.includes(value))
        throw new InputError(`${where} must be one of ${row.choices.join(', ')}, not ${JSON.stringify(value)}`);
      return value;
    case 'integer':
    case 'number':
      if (typeof value !== 'number' || !Number.isFinite(value))
        throw new InputError(`${where} must be a finite number, not ${JSON.stringify(value)}`);
      if (row.kind === 'integer' && !Number.isInteger(value))
        throw new InputError(`${where} must be an integer, not ${value}`);
      if (value < row.min || value > row.max)
        throw new InputError(`${where} must lie in [${row.min}, ${row.max}], not ${value}`);
      return value;
    default:
      throw new InputError(`${where} has an unknown kind ${row.kind}`);
  }
}

// The complete settings of one load: every declared key, the given value or its default.
// A key that is not declared is an error, never ignored.
export function checkSettings(table, given) {
  const byKey = new Map(table.map((row) => [row.key, row]));
  for (const key of Object.keys(given))
    if (!byKey.has(key))
      throw new InputError(`unknown setting "${key}" (this engine has ${table.map((r) => r.key).join(', ')})`);
  const settings = {};
  for (const row of table) settings[row.key] = row.key in given ? checkValue(row, given[row.key]) : row.default;
  return settings;
}
