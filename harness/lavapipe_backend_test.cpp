// smoke tests land with the backend
