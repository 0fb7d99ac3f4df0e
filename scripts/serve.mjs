// Serves the web app with Vite's dev server (`npm start` runs this after scripts/bootstrap.sh).
//   HOST=0.0.0.0 PORT=8080 node scripts/serve.mjs
// Binds to 127.0.0.1 unless HOST says otherwise: the app is for the person at this machine. When the
// port is taken, Vite tries the next ones; the line printed names the port actually used.
import { fileURLToPath } from 'node:url';
import { createServer } from 'vite';

const webRoot = fileURLToPath(new URL('../web/', import.meta.url));
const host = process.env.HOST || '127.0.0.1';
const port = Number(process.env.PORT || 5173);
if (!Number.isInteger(port) || port < 0 || port > 65535) {
  console.error(`serve: PORT must be a port number, not "${process.env.PORT}"`);
  process.exit(2);
}

const server = await createServer({
  root: webRoot,
  configFile: fileURLToPath(new URL('vite.config.ts', new URL('../web/', import.meta.url))),
  server: { host, port, strictPort: false },
});
await server.listen();
const address = server.httpServer?.address();
const actualPort = typeof address === 'object' && address ? address.port : port;
const shownHost = host.includes(':') ? `[${host}]` : host;
console.log(`geoshift is running at http://${shownHost}:${actualPort}/`);

let closing = false;
for (const signal of ['SIGINT', 'SIGTERM']) {
  process.on(signal, async () => {
    if (closing) return;
    closing = true;
    await server.close();
    process.exit(0);
  });
}
