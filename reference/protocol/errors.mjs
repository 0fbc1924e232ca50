// An error in what boxpile sent (a request, a setting, the scene): answered as {"ok": false}
// with its message alone. Any other exception is an adapter or engine fault and is answered
// the same way, with its stack written to standard error as well.
export class InputError extends Error {}
